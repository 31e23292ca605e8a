"""A UR5 described as Universal Robots' ROS package describes it (the joint origins, rpy and axes
of ur_description's ur5_robot.urdf, as example-robot-data ships it; the meshes and inertias left
out): joints about the y axes of their frames, not DH rows. Chain.from_urdf(UR5_URDF, "base",
"tool0") has the kinematics of rk.robots.ur5()."""

_JOINTS = [  # name, parent, child, rpy, xyz, axis
    ("shoulder_pan_joint", "base_link", "shoulder_link", "0 0 0", "0 0 0.089159", "0 0 1"),
    ("shoulder_lift_joint", "shoulder_link", "upper_arm_link", "0 1.57079632679 0", "0 0.13585 0", "0 1 0"),
    ("elbow_joint", "upper_arm_link", "forearm_link", "0 0 0", "0 -0.1197 0.425", "0 1 0"),
    ("wrist_1_joint", "forearm_link", "wrist_1_link", "0 1.57079632679 0", "0 0 0.39225", "0 1 0"),
    ("wrist_2_joint", "wrist_1_link", "wrist_2_link", "0 0 0", "0 0.093 0", "0 0 1"),
    ("wrist_3_joint", "wrist_2_link", "wrist_3_link", "0 0 0", "0 0 0.09465", "0 1 0"),
]
_FIXED = [
    ("ee_fixed_joint", "wrist_3_link", "ee_link", "0 0 1.57079632679", "0 0.0823 0"),
    ("base_link-base_fixed_joint", "base_link", "base", "0 0 -3.14159265359", "0 0 0"),
    ("wrist_3_link-tool0_fixed_joint", "wrist_3_link", "tool0", "-1.57079632679 0 0", "0 0.0823 0"),
]


def _urdf():
    links = {"base_link"} | {j[2] for j in _JOINTS} | {j[2] for j in _FIXED}
    out = ['<robot name="ur5">'] + [f'  <link name="{n}"/>' for n in sorted(links)]
    for name, parent, child, rpy, xyz, axis in _JOINTS:
        out.append(f'  <joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
                   f'<origin rpy="{rpy}" xyz="{xyz}"/><axis xyz="{axis}"/>'
                   '<limit effort="150" lower="-6.28318530718" upper="6.28318530718" velocity="3.15"/></joint>')
    for name, parent, child, rpy, xyz in _FIXED:
        out.append(f'  <joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/>'
                   f'<origin rpy="{rpy}" xyz="{xyz}"/></joint>')
    return "\n".join(out + ["</robot>"])


UR5_URDF = _urdf()
