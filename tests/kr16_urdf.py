"""A KUKA KR 16-2 described as ROS-Industrial's kuka_kr16_support package describes it (the joint
origins, axes and limits of kr16_2_macro.xacro; meshes and inertias left out): joint 1 about -z,
joints 4 and 6 about -x, a spherical wrist 35 mm below the forearm's line, the flange 158 mm past
the wrist centre. Chain.from_urdf(KR16_URDF) runs from base_link to tool0 (the controller's
$FLANGE frame)."""

import math

_D = math.pi / 180
_JOINTS = [  # name, parent, child, xyz, axis, lower (deg), upper (deg)
    ("joint_a1", "base_link", "link_1", "0 0 0.675", "0 0 -1", -185, 185),
    ("joint_a2", "link_1", "link_2", "0.26 0 0", "0 1 0", -155, 35),
    ("joint_a3", "link_2", "link_3", "0.68 0 0", "0 1 0", -130, 154),
    ("joint_a4", "link_3", "link_4", "0.67 0 -0.035", "-1 0 0", -350, 350),
    ("joint_a5", "link_4", "link_5", "0 0 0", "0 1 0", -130, 130),
    ("joint_a6", "link_5", "link_6", "0 0 0", "-1 0 0", -350, 350),
]


def _urdf():
    links = ["base_link"] + [j[2] for j in _JOINTS] + ["tool0"]
    out = ['<robot name="kuka_kr16_2">'] + [f'  <link name="{n}"/>' for n in links]
    for name, parent, child, xyz, axis, lower, upper in _JOINTS:
        out.append(f'  <joint name="{name}" type="revolute"><parent link="{parent}"/><child link="{child}"/>'
                   f'<origin xyz="{xyz}" rpy="0 0 0"/><axis xyz="{axis}"/>'
                   f'<limit effort="0" lower="{lower * _D!r}" upper="{upper * _D!r}" velocity="2.7"/></joint>')
    out.append('  <joint name="joint_a6-tool0" type="fixed"><parent link="link_6"/><child link="tool0"/>'
               f'<origin xyz="0.158 0 0" rpy="0 {90 * _D!r} 0"/></joint>')
    return "\n".join(out + ["</robot>"])


KR16_URDF = _urdf()
