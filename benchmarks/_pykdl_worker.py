"""PyKDL reference, run by bench_chain.py under Debian's /usr/bin/python3 (python3-pykdl).

Reads a JSON request on stdin: {"robots": {name: {"segments": [...], "q": [...]}}}, where each
segment is [joint, axis, tip] with joint "R", "P", "F", "RZ" or "PZ", axis a 3-list and tip a row-major 4x4.
Builds the same KDL chains, times FK (list -> JntArray conversion included) and the Jacobian with
the same timing method as the parent (benchmarks/_timing.py), and writes JSON with the timings and
the values at q so that the parent can check them against robokin.
"""

import json
import sys

import PyKDL as kdl

from _timing import per_call


def frame(m):
    rot = kdl.Rotation(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2])
    return kdl.Frame(rot, kdl.Vector(m[0][3], m[1][3], m[2][3]))


def build(segments):
    chain = kdl.Chain()
    for joint, axis, tip in segments:
        if joint == "F":
            j = kdl.Joint(kdl.Joint.Fixed)
        elif joint in ("RZ", "PZ"):  # what robokin's from_dh builds: KDL's RotZ / TransZ joints
            j = kdl.Joint(kdl.Joint.RotZ if joint == "RZ" else kdl.Joint.TransZ)
        else:
            kind = kdl.Joint.RotAxis if joint == "R" else kdl.Joint.TransAxis
            j = kdl.Joint(kdl.Vector(0, 0, 0), kdl.Vector(*axis), kind)
        chain.addSegment(kdl.Segment(j, frame(tip)))
    return chain


def main():
    request = json.load(sys.stdin)
    out = {"version": getattr(kdl, "__version__", "?"), "robots": {}}
    for name, spec in request["robots"].items():
        chain = build(spec["segments"])
        n = chain.getNrOfJoints()
        fk = kdl.ChainFkSolverPos_recursive(chain)
        jac = kdl.ChainJntToJacSolver(chain)
        ns = {"kdl": kdl, "fk": fk, "jac": jac, "ql": list(spec["q"]), "n": n,
              "f": kdl.Frame(), "J": kdl.Jacobian(n)}
        to_jnt = "j = kdl.JntArray(n)\nfor i in range(n): j[i] = ql[i]\n"
        fk_stmt = to_jnt + "fk.JntToCart(j, f)"
        jac_stmt = to_jnt + "jac.JntToJac(j, J)"
        exec(fk_stmt, ns)
        exec(jac_stmt, ns)
        f, J = ns["f"], ns["J"]
        out["robots"][name] = {
            "fk": per_call(fk_stmt, ns),
            "jacobian": per_call(jac_stmt, ns),
            "fk_value": [[f.M[r, c] for c in range(3)] + [f.p[r]] for r in range(3)] + [[0, 0, 0, 1]],
            "jacobian_value": [[J[r, c] for c in range(n)] for r in range(6)],
        }
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
