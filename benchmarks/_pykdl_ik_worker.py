"""PyKDL's IK reference, run by bench_ik_defaults.py under Debian's /usr/bin/python3 (python3-pykdl).

Reads JSON on stdin: {arm: {"segments": [[joint, axis, tip], ...], "targets": [4x4, ...], "q0": [...]}}
(joint "R" about axis through the segment's start, or "F" fixed; tip row-major 4x4). Builds the KDL
chain, solves every target with ChainIkSolverPos_LMA (KDL's defaults: eps 1e-5, 500 iterations)
from q0, timing each call as a PyKDL user writes it (list -> JntArray and Frame conversion
included), and writes JSON: {arm: {"q": [...], "times": [...], "codes": [KDL's code >= 0, ...], "fk_q": [...],
"fk_check": [...]}},
the last two being PyKDL's FK at a few joint vectors so that the parent can check the chain.
"""

import json
import sys
import time

import PyKDL as kdl


def frame(m):
    rot = kdl.Rotation(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2])
    return kdl.Frame(rot, kdl.Vector(m[0][3], m[1][3], m[2][3]))


def build(segments):
    chain = kdl.Chain()
    for joint, axis, tip in segments:
        if joint == "F":
            j = kdl.Joint(kdl.Joint.Fixed)
        else:
            j = kdl.Joint(kdl.Vector(0, 0, 0), kdl.Vector(*axis), kdl.Joint.RotAxis)
        chain.addSegment(kdl.Segment(j, frame(tip)))
    return chain


def main():
    request = json.load(sys.stdin)
    out = {}
    for name, spec in request.items():
        chain = build(spec["segments"])
        n = chain.getNrOfJoints()
        solver = kdl.ChainIkSolverPos_LMA(chain)
        fk = kdl.ChainFkSolverPos_recursive(chain)
        q0 = kdl.JntArray(n)
        for i, v in enumerate(spec["q0"]):
            q0[i] = v
        qs, times, codes = [], [], []
        for m in spec["targets"]:
            t = time.perf_counter()
            target = frame(m)
            q = kdl.JntArray(n)
            code = solver.CartToJnt(q0, target, q)
            times.append(time.perf_counter() - t)
            qs.append([q[i] for i in range(n)])
            codes.append(code >= 0)
        fk_q = qs[:5]
        fk_check = []
        for ql in fk_q:
            j = kdl.JntArray(n)
            for i, v in enumerate(ql):
                j[i] = v
            f = kdl.Frame()
            fk.JntToCart(j, f)
            fk_check.append([[f.M[r, c] for c in range(3)] + [f.p[r]] for r in range(3)] + [[0, 0, 0, 1]])
        out[name] = {"q": qs, "times": times, "codes": codes, "fk_q": fk_q, "fk_check": fk_check}
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
