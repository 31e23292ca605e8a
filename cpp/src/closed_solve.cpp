// The closed form of the arms closed_family recognises, from the Paden-Kahan subproblems.
#include "robokin/closed_solve.hpp"
#include "robokin/parallel.hpp"

#include "closed_batch.hpp"
#include "posture_label.hpp"
#include "kernel/fast_math.hpp"
#include "robokin/subproblems.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace robokin {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

// The candidates of one solve, checked together at the end: each joint's turn, its angle taken
// with every other's in one pass of arc tangents (angles()).
struct Candidates {
  double c[48], s[48];  // joint i of candidate k: its turn's cosine and sine at 6 k + i
  int shoulder[8], elbow[8], wrist[8];
  int m = 0;
  bool singular = false;
  void add(const Turn* joints, int sh, int e, int w) {
    if (m == 8) return;
    for (int i = 0; i < 6; ++i) c[6 * m + i] = joints[i].c, s[6 * m + i] = joints[i].s;
    shoulder[m] = sh, elbow[m] = e, wrist[m++] = w;
  }
  // The candidates' angles, rows of 6 into out. A joint's turn equal to the previous candidate's
  // (candidates of one wrist share joints 1 to 3) is taken once.
  void angles(double* out) const {
    double y[48], x[48], t[48];
    int at[48], u = 0;
    for (int j = 0; j < 6 * m; ++j) {
      if (j >= 6 && c[j] == c[j - 6] && s[j] == s[j - 6]) {
        at[j] = at[j - 6];
        continue;
      }
      y[u] = s[j], x[u] = c[j], at[j] = u++;
    }
    vmath::atan2(y, x, t, u);
    for (int j = 0; j < 6 * m; ++j) out[j] = t[at[j]];
  }
};

// The elbow's label: e (on axis 3) against the line from s (axis 2) to w (the wrist), in the plane
// normal to n (axis 2), towards `up` (axis 1) or away; straight / folded when the 2R is singular.
int elbow_label(const V3& s, const V3& e, const V3& w, const V3& n, const V3& up, bool singular) {
  const V3 d = (w - s) - (w - s).dot(n) * n, f = (e - s) - (e - s).dot(n) * n;
  if (singular) return f.dot(d) > 0 && (w - s).norm() >= (e - s).norm() ? 2 : 3;
  const double dd = d.squaredNorm();
  const V3 perp = dd > 0 ? V3(f - (f.dot(d) / dd) * d) : f;
  return perp.dot(up) > 0 ? 0 : 1;
}

// The wrist's label at the solution: the sign of (a4 x a6) . a5.
int wrist_label(const V3& a4, const V3& a5, const V3& a6, bool singular) {
  if (singular) return 2;
  return a4.cross(a6).dot(a5) >= 0 ? 0 : 1;
}

// q1 of each shoulder (subproblem 4: the wrist point c keeps its height along axis 2 under joints
// 2 .. 6), with its label.
SubproblemAngles shoulders(const JointAxes& g, const V3& c, const V3& center) {
  SubproblemAngles t = subproblem4(g.axis[1], g.axis[0], c - g.point[0], g.axis[1].dot(center - g.point[0]));
  for (int i = 0; i < t.count; ++i) t.turn[i] = -t.turn[i];
  return t;
}

int shoulder_label(const JointAxes& g, const M3& R1, const V3& c, bool singular) {
  if (singular) return 2;
  const V3 x1 = g.axis[0].cross(R1 * g.axis[1]);
  return x1.dot(c - g.point[0]) > 0 ? 1 : 0;
}

// What a spherical wrist turns towards at the target G: the tool's axis 6 and a unit vector x normal
// to it (fixed in the last link), as the base sees them (G.R h6, G.R x); y = h6 x x. And the
// subproblem 2 of its axes 4, 5 turning axis 6, prepared once for the solve's wrists.
struct WristGoal {
  V3 x, y, h6, x6;
  Subproblem2 turns;
};

WristGoal wrist_goal(const JointAxes& g, const Rigid& G) {
  const V3 x = g.axis[5].unitOrthogonal();
  return {x, g.axis[5].cross(x), G.R * g.axis[5], G.R * x, Subproblem2(g.axis[3], g.axis[4], g.axis[5])};
}

// The spherical wrist of q1 .. q3 (R03 their rotation): (q4, q5) by subproblem 2 on axis 6, q6 by
// subproblem 1 on x.
void wrist(const JointAxes& g, const WristGoal& goal, const M3& R03, Turn* q, int s, int e, Candidates& out) {
  const V3 &h4 = g.axis[3], &h5 = g.axis[4], &h6 = g.axis[5];
  const V3 w6 = R03.transpose() * goal.h6, wx = R03.transpose() * goal.x6;  // R4 R5 R6 h6, R4 R5 R6 x
  SubproblemAngles t4, t5;
  const bool aligned = h4.cross(w6).squaredNorm() < 1e-18;  // axes 4 and 6 aligned (1e-9): q4 + q6 only
  if (aligned) {
    t4.count = 1;
    t5 = subproblem1(h5, h6, w6);
    out.singular = true;
  } else {
    goal.turns.solve(w6, t4, t5);
  }
  for (int i = 0; i < t4.count; ++i) {
    q[3] = t4.turn[i], q[4] = t5.turn[aligned ? 0 : i];
    // q6 turns x onto R6 x = (R4 R5)^T wx, in the plane (x, y) normal to h6: subproblem 1 on
    // orthonormal data.
    const V3 v = rotate(h5, -q[4], rotate(h4, -q[3], wx));
    q[5] = direction(goal.x.dot(v), goal.y.dot(v));
    // The label's triple product (a4 x a6) . a5, with a4 = R03 h4, a5 = R03 R4 h5, a6 = R03 R4 R5 h6,
    // is the same seen after joint 4 (R03 R4 a rotation, fixing h4).
    out.add(q, s, e, wrist_label(h4, h5, rotate(h5, q[4], h6), aligned));
  }
}

// Spherical wrist, axes 2, 3 parallel: the wrist centre c by q1 (4), q3 (3), q2 (1).
void solve_spherical(const JointAxes& g, const V3& center, const Rigid& G, Candidates& out) {
  const V3 c = G.R * center + G.p;
  const WristGoal goal = wrist_goal(g, G);
  const V3 &p1 = g.point[0], &p2 = g.point[1], &p3 = g.point[2];
  const SubproblemAngles t1 = shoulders(g, c, center);
  out.singular = out.singular || t1.singular;
  for (int i = 0; i < t1.count; ++i) {
    Turn q[6] = {t1.turn[i]};
    const M3 R1 = axis_rotation(g.axis[0], q[0]);
    const int s = shoulder_label(g, R1, c, t1.singular);
    const V3 v = R1.transpose() * (c - p1) - (p2 - p1);
    const SubproblemAngles t3 = subproblem3(g.axis[2], center - p3, p2 - p3, v.norm());
    out.singular = out.singular || t3.singular;
    for (int j = 0; j < t3.count; ++j) {
      q[2] = t3.turn[j];
      const M3 R3 = axis_rotation(g.axis[2], q[2]);
      q[1] = subproblem1(g.axis[1], (p3 - p2) + R3 * (center - p3), v).turn[0];
      const M3 R12 = R1 * axis_rotation(g.axis[1], q[1]);
      const V3 s2 = p1 + R1 * (p2 - p1), e3 = s2 + R12 * (p3 - p2);
      const int e = elbow_label(s2, e3, c, R1 * g.axis[1], g.axis[0], t3.singular);
      wrist(g, goal, R12 * R3, q, s, e, out);
    }
  }
}

// Spherical wrist, axes 1, 2 meeting at s: q3 (3) keeps the wrist centre |c - s| from s, then q1,
// q2 (2) turn it onto c. The elbow's label: the turn about axis 3 from s to c.
void solve_meet(const JointAxes& g, const V3& center, const V3& s, const Rigid& G, Candidates& out) {
  const V3 c = G.R * center + G.p;
  const WristGoal goal = wrist_goal(g, G);
  const V3 &h3 = g.axis[2], &p3 = g.point[2];
  const SubproblemAngles t3 = subproblem3(h3, center - p3, s - p3, (c - s).norm());
  out.singular = out.singular || t3.singular;
  for (int j = 0; j < t3.count; ++j) {
    Turn q[6];
    q[2] = t3.turn[j];
    const M3 R3 = axis_rotation(h3, q[2]);
    SubproblemAngles t1, t2;
    subproblem2(g.axis[0], g.axis[1], (p3 - s) + R3 * (center - p3), c - s, t1, t2);
    out.singular = out.singular || t1.singular || t2.singular;
    for (int i = 0; i < t1.count; ++i) {
      q[0] = t1.turn[i], q[1] = t2.turn[i];
      const M3 R1 = axis_rotation(g.axis[0], q[0]), R12 = R1 * axis_rotation(g.axis[1], q[1]);
      const V3 a3 = R12 * h3, p3w = s + R12 * (p3 - s);
      const V3 e = p3w + (s - p3w).dot(a3) * a3;
      const int elbow = t3.singular ? ((e - s).dot(c - e) >= 0 ? 2 : 3) : (a3.dot((s - e).cross(c - e)) > 0 ? 0 : 1);
      wrist(g, goal, R12 * R3, q, shoulder_label(g, R1, c, t1.singular), elbow, out);
    }
  }
}

// Spherical wrist, axes 2, 3 meeting at s after axis 1: joints 2, 3 fix s, so q1 (3) puts the
// wrist centre c at |c0 - s| from s as seen before joint 1, then q2, q3 (2) turn c0 onto it. The
// shoulder's label: the turn about axis 1 from s (at the solution) to c; the elbow's: the turn
// about axis 3 from axis 2 to c (straight / folded where they are coplanar: axis 3 between the two
// or not).
void solve_meet_after(const JointAxes& g, const V3& center, const V3& s, const Rigid& G, Candidates& out) {
  const V3 c = G.R * center + G.p;
  const WristGoal goal = wrist_goal(g, G);
  const V3 &h1 = g.axis[0], &p1 = g.point[0], &h2 = g.axis[1], &h3 = g.axis[2];
  const SubproblemAngles t1 = subproblem3(h1, s - p1, c - p1, (center - s).norm());
  out.singular = out.singular || t1.singular;
  for (int i = 0; i < t1.count; ++i) {
    Turn q[6] = {t1.turn[i]};
    const M3 R1 = axis_rotation(h1, q[0]);
    const V3 s1 = p1 + R1 * (s - p1), w = c - s1;
    const int shoulder = t1.singular ? 2 : (h1.dot((s1 - p1).cross(c - p1)) > 0 ? 0 : 1);
    SubproblemAngles t2, t3;
    subproblem2(h2, h3, center - s, R1.transpose() * (c - p1) + (p1 - s), t2, t3);
    const bool elbow_singular = t2.singular || t3.singular;
    out.singular = out.singular || elbow_singular;
    for (int j = 0; j < t2.count; ++j) {
      q[1] = t2.turn[j], q[2] = t3.turn[j];
      const M3 R12 = R1 * axis_rotation(h2, q[1]), R3 = axis_rotation(h3, q[2]);
      const V3 a2 = R1 * h2, a3 = R12 * h3;
      const int elbow = elbow_singular ? (a2.cross(a3).dot(a3.cross(w)) > 0 ? 2 : 3)
                                       : (a3.dot(a2.cross(w)) > 0 ? 0 : 1);
      wrist(g, goal, R12 * R3, q, shoulder, elbow, out);
    }
  }
}

// The motion of joint i of g turned by t (a rotation about its axis through its point).
Rigid joint_motion(const JointAxes& g, int i, const Turn& t) {
  Rigid E;
  E.R = axis_rotation(g.axis[i], t);
  E.p = g.point[i] - E.R * g.point[i];
  return E;
}

// Three parallel axes 1, 2, 3 (direction h), axes 5, 6 meeting at c0: joints 1 to 3 keep heights
// along h and turn about h, so q4 (4) restores c's height and q5, q6 (2) turn h as the tool sees it
// back onto h as joint 4 leaves it; joints 1 to 3, M = G (E4 E5 E6)^-1, are a planar arm moving axis
// 3's point p3 to w = M p3: q1 (3), q2 (1), q3 from M's turn about h. Labels: the shoulder the turn
// about axis 4 from h to c, the elbow the planar arm's turn at axis 2, the wrist (a5 x a6) . h.
void solve_parallel_first(const JointAxes& g, const V3& center, const Rigid& G, Candidates& out) {
  const V3 c = G.R * center + G.p;
  const V3 &h = g.axis[0], &h4 = g.axis[3], &h5 = g.axis[4], &h6 = g.axis[5];
  const V3 &p1 = g.point[0], &p2 = g.point[1], &p3 = g.point[2];
  // Axes 2 and 3 may point against axis 1 (parallel lines): R(h2, q) = R(h, s2 q).
  const double s2 = g.axis[1].dot(h) > 0 ? 1.0 : -1.0, s3 = g.axis[2].dot(h) > 0 ? 1.0 : -1.0;
  const SubproblemAngles t4 = subproblem4(h, h4, center - g.point[3], h.dot(c - g.point[3]));
  out.singular = out.singular || t4.singular;
  for (int i = 0; i < t4.count; ++i) {
    Turn q[6];
    q[3] = t4.turn[i];
    SubproblemAngles t5, t6;
    subproblem2(h5, h6, G.R.transpose() * h, rotate(h4, -q[3], h), t5, t6);
    const bool wrist_singular = t5.singular || t6.singular;
    out.singular = out.singular || wrist_singular;
    for (int k = 0; k < t5.count; ++k) {
      q[4] = t5.turn[k], q[5] = t6.turn[k];
      const Rigid E4 = joint_motion(g, 3, q[3]), E45 = E4 * joint_motion(g, 4, q[4]);
      const Rigid M = G * (E45 * joint_motion(g, 5, q[5])).inverse();  // E1 E2 E3
      const V3 w = M.R * p3 + M.p;
      const SubproblemAngles t1 = subproblem3(h, p2 - p1, w - p1, (p3 - p2).norm());
      out.singular = out.singular || t1.singular;
      const V3 x = h.unitOrthogonal();
      const Turn q123 = subproblem1(h, x, M.R * x).turn[0];
      const Rigid M4 = M * E4, M5 = M * E45;
      const V3 a4 = M.R * h4, o4 = M.R * g.point[3] + M.p;
      const int shoulder = t4.singular ? 2 : (a4.dot(h.cross(c - o4)) > 0 ? 0 : 1);
      const int wrist = wrist_singular ? 2 : ((M4.R * h5).cross(M5.R * h6).dot(h) >= 0 ? 0 : 1);
      for (int j = 0; j < t1.count; ++j) {
        q[0] = t1.turn[j];
        q[1] = subproblem1(g.axis[1], p3 - p2, rotate(h, -q[0], w - p1) + (p1 - p2)).turn[0];
        q[2] = (q123 - q[0] - q[1].times(s2)).times(s3);
        const V3 o2 = p1 + rotate(h, q[0], p2 - p1), arm = o2 - p1, fore = w - o2;
        const int elbow = t1.singular ? (arm.dot(fore) > 0 ? 2 : 3) : (h.dot(arm.cross(fore)) > 0 ? 0 : 1);
        out.add(q, shoulder, elbow, wrist);
      }
    }
  }
}

// q6 (into q6) and q2 + q3 + q4 (returned) of the three-parallel family for q1 and q5: R16 = R1^T
// R06, A the wrist point seen from axis 2 (A = R1^T (c - p1) - (p2 - p1)). At the wrist's
// singularity (axis 6 parallel to axis 2: only q234 +- q6 is fixed; `singular` set) the
// representative puts the elbow at a right angle, or as near as the continuum allows.
Turn parallel_wrist(const JointAxes& g, const V3& center, const M3& R16, const M3& R5, const V3& A, bool& singular,
                    Turn& q6) {
  const V3 &h2 = g.axis[1], &h6 = g.axis[5];
  const SubproblemAngles t6 = subproblem1(h6, R5.transpose() * h2, R16.transpose() * h2);
  if (!(singular || t6.singular)) {
    q6 = -t6.turn[0];
    const V3 y = h2.unitOrthogonal();
    return subproblem1(h2, y, R16 * (R5 * axis_rotation(h6, q6)).transpose() * y).turn[0];
  }
  singular = true;
  const auto flat = [&](const V3& x) { return V3(x - x.dot(h2) * h2); };
  const V3 a = flat(A), b = flat(center - g.point[3]);
  const double l2 = flat(g.point[2] - g.point[1]).squaredNorm(), l3 = flat(g.point[3] - g.point[2]).squaredNorm();
  const double reach = a.norm() * b.norm() * (1.0 - 1e-12);
  const double d = std::clamp(0.5 * (a.squaredNorm() + b.squaredNorm() - l2 - l3), -reach, reach);
  const SubproblemAngles t = subproblem4(a, h2, b, d);
  const Turn q234 = t.count ? t.turn[0] : Turn{};
  const V3 x = h6.unitOrthogonal();
  q6 = subproblem1(h6, x, R5.transpose() * rotate(h2, -q234, R16 * x)).turn[0];
  return q234;
}

// Three parallel axes 2, 3, 4 (axes 5, 6 meeting at c): per q1, q5 (4) and q6 (1), then q234 (1)
// and the planar arm of joints 2, 3 (3, 1). q234 is the angle about axis 2 of joints 2, 3, 4 together.
void solve_parallel(const JointAxes& g, const V3& center, const Rigid& G, Candidates& out) {
  const V3 c = G.R * center + G.p;
  const V3 &h2 = g.axis[1], &h5 = g.axis[4], &h6 = g.axis[5];
  const V3 &p1 = g.point[0], &p2 = g.point[1], &p3 = g.point[2], &p4 = g.point[3];
  // Axes 3 and 4 may point against axis 2 (parallel lines): R(h3, q3) = R(h2, s3 q3).
  const double s3 = g.axis[2].dot(h2) > 0 ? 1.0 : -1.0, s4 = g.axis[3].dot(h2) > 0 ? 1.0 : -1.0;
  const SubproblemAngles t1 = shoulders(g, c, center);
  out.singular = out.singular || t1.singular;
  for (int i = 0; i < t1.count; ++i) {
    Turn q[6] = {t1.turn[i]};
    const M3 R1 = axis_rotation(g.axis[0], q[0]), R16 = R1.transpose() * G.R;
    const int s = shoulder_label(g, R1, c, t1.singular);
    const SubproblemAngles t5 = subproblem4(h2, h5, h6, h2.dot(R16 * h6));
    for (int k = 0; k < t5.count; ++k) {
      q[4] = t5.turn[k];
      const M3 R5 = axis_rotation(h5, q[4]);
      const V3 A = R1.transpose() * (c - p1) - (p2 - p1);
      bool wrist_singular = t5.singular && t5.count == 1;  // q5 exactly at the singularity
      Turn q234 = parallel_wrist(g, center, R16, R5, A, wrist_singular, q[5]);
      V3 v = A - rotate(h2, q234, center - p4);
      SubproblemAngles t3 = subproblem3(g.axis[2], p4 - p3, p2 - p3, v.norm());
      if (t3.count == 0 && t5.singular && !wrist_singular) {
        // Within the margin of the wrist's singularity q234 is split from q6 by rounding alone and
        // may leave the elbow out of reach: the representative instead (polished in closed_solve).
        wrist_singular = true;
        q234 = parallel_wrist(g, center, R16, R5, A, wrist_singular, q[5]);
        v = A - rotate(h2, q234, center - p4);
        t3 = subproblem3(g.axis[2], p4 - p3, p2 - p3, v.norm());
      }
      out.singular = out.singular || wrist_singular || t5.singular;
      out.singular = out.singular || t3.singular;
      for (int j = 0; j < t3.count; ++j) {
        q[2] = t3.turn[j];
        const M3 R3 = axis_rotation(g.axis[2], q[2]);
        q[1] = subproblem1(h2, (p3 - p2) + R3 * (p4 - p3), v).turn[0];
        q[3] = (q234 - q[1] - q[2].times(s3)).times(s4);
        const M3 R12 = R1 * axis_rotation(h2, q[1]), R13 = R12 * R3, R14 = R13 * axis_rotation(g.axis[3], q[3]);
        const V3 s2 = p1 + R1 * (p2 - p1), e3 = s2 + R12 * (p3 - p2), w4 = e3 + R13 * (p4 - p3);
        const int e = elbow_label(s2, e3, w4, R1 * h2, g.axis[0], t3.singular);
        out.add(q, s, e, wrist_label(R14 * g.axis[3], R14 * h5, R14 * (R5 * h6), wrist_singular));
      }
    }
  }
}

// Newton steps on the chain's forward model from a candidate that misses T by rounding alone: near a
// singularity a subproblem's two solutions are taken as one (a cosine within kSubproblemEps of 1,
// ~1e-6 rad) and the angles that follow carry that error. The pseudo-inverse (singular values below
// 1e-10 of the largest dropped) takes the least step, moving every joint but the held one. F is the
// candidate's frame, updated.
void polish(const Chain& chain, const Rigid& T, int held, double* q, Rigid& F) {
  const int n = chain.dof();
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, ClosedFormSolutions::kMaxDof> Jfull(6, n);
  Eigen::Matrix<double, 6, 6> J;
  for (int step = 0; step < 4; ++step) {
    chain.fk_jacobian(q, F, Jfull.data());
    for (int i = 0, k = 0; i < n; ++i)
      if (i != held) J.col(k++) = Jfull.col(i);
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = T.p - F.p;
    const Eigen::AngleAxisd turn(T.R * F.R.transpose());
    e.tail<3>() = turn.angle() * turn.axis();
    if (e.norm() == 0.0) return;
    const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const auto& sv = svd.singularValues();
    Eigen::Matrix<double, 6, 1> dq = Eigen::Matrix<double, 6, 1>::Zero(), ut = svd.matrixU().transpose() * e;
    for (int i = 0; i < 6; ++i)
      if (sv(i) > 1e-10 * sv(0)) dq += (ut(i) / sv(i)) * svd.matrixV().col(i);
    for (int i = 0, k = 0; i < n; ++i)
      if (i != held) q[i] += dq(k++);
  }
  chain.fk(q, F);
}

}  // namespace

ClosedArm read_closed_arm(const Chain& chain, const ClosedFamilyOptions& options,
                          const std::optional<HeldJoint>& held) {
  ClosedArm arm;
  arm.axes = joint_axes(chain, held);
  arm.family = closed_family(arm.axes, options, &arm.solved);
  if (held) arm.held_cos = std::cos(held->value), arm.held_sin = std::sin(held->value);
  return arm;
}

ClosedArm closed_arm(const Chain& chain, const ClosedFamilyOptions& options, const std::optional<HeldJoint>& held) {
  ClosedArm arm = read_closed_arm(chain, options, held);
  if (arm.family.kind == FamilyKind::None)
    throw std::invalid_argument(std::string(held ? "locked" : "chain") + ": no closed form for this arm" +
                                (held ? " with q[" + std::to_string(held->joint) + "] held" : "") + " (" +
                                arm.family.reason + ")");
  return arm;
}

namespace {

// The held joint's index in q, or -1.
int held_index(const ClosedArm& arm) { return arm.axes.held ? static_cast<int>(arm.axes.held->joint) : -1; }

// The candidates of the arm's family for T as the chain's joint vectors, packed (rows of n =
// chain.dof() values into q, their turns' cosines and sines into tc, ts): read back from the
// reversed axes, the held joint's value in its place.
int candidates(const ClosedArm& arm, const Rigid& T, Candidates& c, double* q, double* tc, double* ts) {
  Rigid G = T * arm.axes.tool.inverse();  // E1 ... E6: the joints' motion
  if (arm.family.reversed) G = G.inverse();
  const FamilyKind kind = arm.family.kind;
  const JointAxes& g = arm.family.reversed ? arm.solved : arm.axes;
  if (kind == FamilyKind::ThreeParallel) solve_parallel(g, arm.family.center, G, c);
  else if (kind == FamilyKind::WristMeet) solve_meet(g, arm.family.center, arm.family.shoulder, G, c);
  else if (kind == FamilyKind::WristMeetAfter) solve_meet_after(g, arm.family.center, arm.family.shoulder, G, c);
  else if (kind == FamilyKind::ParallelFirst) solve_parallel_first(g, arm.family.center, G, c);
  else solve_spherical(g, arm.family.center, G, c);
  double angles[8 * 6];
  c.angles(angles);
  const int n = 6 + arm.axes.held.has_value(), held = held_index(arm);
  for (int k = 0; k < c.m; ++k)
    for (int i = 0, j = 0; i < n; ++i) {
      if (i == held) {
        q[k * n + i] = arm.axes.held->value, tc[k * n + i] = arm.held_cos, ts[k * n + i] = arm.held_sin;
        continue;
      }
      const int at = 6 * k + (arm.family.reversed ? 5 - j++ : j++);
      q[k * n + i] = angles[at], tc[k * n + i] = c.c[at], ts[k * n + i] = c.s[at];
    }
  return n;
}

}  // namespace

ClosedFormSolutions closed_solve(const ClosedArm& arm, const Chain& chain, const Rigid& T, const JointLimits& limits,
                                 int* slot) {
  ClosedFormSolutions out;
  Candidates c;
  double q[8 * ClosedFormSolutions::kMaxDof], tc[8 * ClosedFormSolutions::kMaxDof], ts[8 * ClosedFormSolutions::kMaxDof];
  const int n = out.dof = candidates(arm, T, c, q, tc, ts);
  out.singular = c.singular;
  if (c.m == 0) return out;
  // The held joint keeps its value as given (within the limits, checked by the caller).
  const int held = held_index(arm);
  bool fits[8];
  fit_limits_rows(q, c.m, n, limits, fits, held);
  // The chain's forward model checks the candidates from their turns (whose arc tangents are q).
  Rigid F[8];
  chain.fk_few_turns(q, tc, ts, c.m, F);
  const double size = std::max(arm.axes.size, 1e-300);
  // A candidate within 1e-4 x the arm's size of T is polished when it misses by more than the check
  // allows; one farther away is no solution (an arc tangent of the wrong branch, a reach clamped).
  for (int k = 0; k < c.m; ++k) {
    bool reaches = closed_reaches(F[k], T, size);
    if (!reaches && (F[k].p - T.p).norm() <= 1e-4 * size) {
      polish(chain, T, held, q + k * n, F[k]);
      fits[k] = fit_limits(q + k * n, n, limits, held);
      chain.fk(q + k * n, F[k]);
      reaches = closed_reaches(F[k], T, size);
    }
    if (!reaches) continue;
    if (slot) slot[out.count()] = posture_slot(c.shoulder[k], c.elbow[k], c.wrist[k]);
    out.add(q + k * n, posture_label(c.shoulder[k], c.elbow[k], c.wrist[k]), fits[k]);
  }
  return out;
}

void closed_solve_batch(const ClosedArm& arm, const Chain& chain, const Rigid* targets, long count,
                        const JointLimits& limits, double* q_out, bool* within_limits, bool* singular,
                        Progress* progress) {
  closed_batch(
      count, 256, chain.dof(), [&](long k, int* slot) { return closed_solve(arm, chain, targets[k], limits, slot); },
      q_out, within_limits, singular, progress);
}

}  // namespace robokin
