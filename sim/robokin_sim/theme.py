"""Colours and sizes of the drawing (one place, so the GIF palette can hold them exactly)."""

BACKGROUND = (250, 250, 247)
GRID = (232, 232, 226)
AXES = (200, 200, 192)
WORKSPACE = (120, 160, 210)
WORKSPACE_FILL = (236, 242, 250)
SINGULAR_CELL = (246, 196, 196)
BASE = (70, 70, 80)
LINK_1 = (40, 90, 160)
LINK_2 = (230, 130, 40)
LEG = (LINK_1, LINK_2)
JOINT_FILL = (255, 255, 255)
JOINT_EDGE = (30, 30, 30)
PLATFORM = (60, 150, 90)
PLATFORM_FILL = (200, 232, 210)
FRAME_X = (210, 50, 50)
FRAME_Y = (50, 160, 60)
PATH = (170, 170, 170)
TRAIL = (200, 40, 120)
TARGET = (20, 20, 20)
TEXT = (25, 25, 30)
TEXT_DIM = (110, 110, 120)
PANEL = (255, 255, 255)
PANEL_EDGE = (190, 190, 185)
CLEAR = (30, 150, 60)
NEAR = (235, 140, 0)
SINGULAR = (215, 30, 30)
BAR = (90, 130, 200)
BAR_BACK = (225, 228, 235)
OVERLAY = (20, 20, 30)
OVERLAY_TEXT = (245, 245, 245)
# Serial arms: links shaded from near to far, joints, the joint axes, the floor, the ellipsoid.
LINK_NEAR = (46, 98, 178)
LINK_FAR = (150, 176, 214)
JOINT_AXIS = (120, 120, 130)
FRAME_Z = (50, 80, 220)
FLOOR = (226, 226, 218)
PEDESTAL = (176, 178, 186)
ELLIPSOID = (150, 60, 170)
SELECTED = (230, 130, 40)

#: Every flat colour above, first in the GIF palette.
COLOURS = [v for k, v in sorted(globals().items()) if k.isupper() and isinstance(v, tuple) and len(v) == 3
           and all(isinstance(c, int) for c in v)]

#: Singularity state -> colour (panel and platform outline).
STATE_COLOURS = {"none": CLEAR, "near": NEAR, "parallel": SINGULAR, "serial": SINGULAR}
