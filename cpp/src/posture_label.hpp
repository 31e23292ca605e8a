// The posture labels of the closed forms ("shoulder left, elbow up, wrist no flip"), one table for
// every arm: a solution keeps the label's pointer, so each label is a string built once.
#pragma once

#include <string>
#include <vector>

namespace robokin {

// shoulder: 0 left, 1 right, 2 singular; elbow: 0 up, 1 down, 2 straight, 3 folded; wrist: 0 no
// flip, 1 flip, 2 singular, or -1 for an arm without a wrist ("shoulder left, elbow up").
inline const char* posture_label(int shoulder, int elbow, int wrist) {
  static const std::vector<std::string> labels = [] {
    const char* const s[] = {"shoulder left", "shoulder right", "shoulder singular"};
    const char* const e[] = {"elbow up", "elbow down", "elbow straight", "elbow folded"};
    const char* const w[] = {"", ", wrist no flip", ", wrist flip", ", wrist singular"};
    std::vector<std::string> all;
    for (const char* a : s)
      for (const char* b : e)
        for (const char* c : w) all.push_back(std::string(a) + ", " + b + c);
    return all;
  }();
  return labels[(shoulder * 4 + elbow) * 4 + wrist + 1].c_str();
}

// The slot of kURPostures (and of a batch's 8 rows) of posture_label's indices: shoulder left 0 /
// right 4, elbow up 0 / down 2, wrist no flip 0 / flip 1; a singular part (or an elbow straight or
// folded) takes the first of the slots it joins.
inline int posture_slot(int shoulder, int elbow, int wrist) {
  return (shoulder == 1) * 4 + (elbow == 1) * 2 + (wrist == 1);
}

}  // namespace robokin
