"""Simulator speed: headless steps per second with and without drawing, and where the time goes.

Targets: >= 300 rendered steps/s headless at 800 x 800 and >= 20,000 steps/s with rendering off
(the seed program was locked at 60 frames per second), and the serial arms' scenes (UR5, PUMA 560)
render at least as many steps per second at 800 x 800 as the 3-RRR scene, measured in the same
process as a ratio of the time per rendered step (median of interleaved runs).
"""

from __future__ import annotations

import os
import time

from _timing import goal

os.environ["SDL_VIDEODRIVER"] = "dummy"
os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")


#: Keys held in free mode: back and forth 2 cm along x, turning a little, so every step moves (a
#: serial arm: Cartesian jog back and forth 4 cm along x; k and l are not its keys).
_FREE = [frozenset({"right", "l"})] * 20 + [frozenset({"left", "k"})] * 20


def _held(mode, k):
    return _FREE[k % len(_FREE)] if mode == "free" else frozenset()


def _make(robot, mode):
    """A new scene of ``robot`` in ``mode`` from the simulator's table."""
    from robokin_sim.config import Config
    from robokin_sim.scenes import SCENES

    return SCENES[robot].scene(Config(robot=robot, mode=mode))


def _scene_steps(scene, mode, steps):
    t0 = time.perf_counter()
    for k in range(steps):
        scene.step(_held(mode, k))
    return time.perf_counter() - t0


def bench_loop(args, render: bool) -> float:
    """Frames per second of the whole headless loop (robokin_sim.loop.run)."""
    from robokin_sim.config import parse_args
    from robokin_sim.loop import run

    res = run(parse_args(["--headless", *args]), render=render)
    return res.frames / res.seconds


def bench_mode(robot: str, mode: str, steps: int = 3000) -> dict:
    """Times the loop's two halves separately on the same scene, at 800 x 800."""
    import pygame

    from robokin_sim.loop import make_renderer
    from robokin_sim.render_common import Hud

    pygame.display.init()

    def make():
        return _make(robot, mode)

    # Kinematics alone (what --headless runs without drawing).
    kin = min(_scene_steps(make(), mode, steps) for _ in range(3))
    # Full rendered loop: step + state + draw, timing each part.
    scene = make()
    surface = pygame.Surface((800, 800))
    renderer = make_renderer(robot, surface.get_size())
    hud = Hud()
    t_step = t_draw = 0.0
    n = steps // 3
    for k in range(n):
        t0 = time.perf_counter()
        scene.step(_held(mode, k))
        t1 = time.perf_counter()
        renderer.draw(surface, scene.state(), hud)
        t2 = time.perf_counter()
        t_step += t1 - t0
        t_draw += t2 - t1
    total = t_step + t_draw
    return {
        "robot": robot, "mode": mode, "steps_per_s_no_render": steps / kin,
        "steps_per_s_rendered": n / total, "kinematics_share": t_step / total, "drawing_share": t_draw / total,
    }


def rendered_step_time(robot: str, mode: str, steps: int = 300) -> float:
    """Seconds per rendered step (step + state + draw at 800 x 800) of a fresh scene."""
    import pygame

    from robokin_sim.loop import make_renderer
    from robokin_sim.render_common import Hud

    pygame.display.init()
    scene = _make(robot, mode)
    surface = pygame.Surface((800, 800))
    renderer = make_renderer(robot, surface.get_size())
    hud = Hud()
    t0 = time.perf_counter()
    for k in range(steps):
        scene.step(_held(mode, k))
        renderer.draw(surface, scene.state(), hud)
    return (time.perf_counter() - t0) / steps


def serial_ratios(repeat: int = 5) -> list:
    """Time per rendered step of the UR5 scene (circle; free mode jogging) over the 3-RRR clover's,
    interleaved runs, medians; the goal is a ratio <= 1."""
    import statistics

    goals = []
    reference = []
    runs = {("ur5", "circle"): [], ("ur5", "free"): [], ("puma560", "free"): []}
    for _ in range(repeat):
        reference.append(rendered_step_time("rrr3", "clover"))
        for key in runs:
            runs[key].append(rendered_step_time(*key))
    ref = statistics.median(reference)
    print(f"rendered steps/s at 800 x 800 (median of {repeat} interleaved runs of 300 steps):")
    print(f"  {'rrr3 clover':<16}{1 / ref:>8,.0f} /s  (reference)")
    for (robot, mode), times in runs.items():
        t = statistics.median(times)
        ratio = t / ref
        what = f"{robot} {mode}" + (" (Cartesian jog)" if mode == "free" else "")
        g = goal(goals, f"simulator: time per rendered step at 800 x 800, {what}", ratio, "x", 1.0,
                 "the 3-RRR clover scene's, same process, interleaved runs")
        print(f"  {what:<16}{1 / t:>8,.0f} /s  time per step {ratio:.2f}x the 3-RRR's  goal <= 1: "
              f"{'met' if g['met'] else 'MISSED'}")
    return goals


def main() -> list:
    print("robokin-sim headless, 800 x 800 (targets: >= 300 rendered steps/s, >= 20,000 steps/s without)")
    frames = ["--mode", "clover", "--frames", "2000"]
    print(f"whole loop, 3-RRR clover: {bench_loop(frames, False):,.0f} steps/s without rendering, "
          f"{bench_loop(frames[:-1] + ['600'], True):,.0f} rendered")
    print(f"{'scene':<14}{'no render /s':>14}{'rendered /s':>13}{'kinematics':>12}{'drawing':>10}")
    for robot, mode in (("rrr3", "free"), ("rrr3", "circle"), ("rrr3", "clover"), ("rpr", "line"), ("ur5", "circle"),
                        ("ur5", "free"), ("panda", "free")):
        r = bench_mode(robot, mode)
        print(f"{robot + ' ' + mode:<14}{r['steps_per_s_no_render']:>14,.0f}{r['steps_per_s_rendered']:>13,.0f}"
              f"{r['kinematics_share']:>11.0%}{r['drawing_share']:>10.0%}")
    print("(per scene: step() alone, then step + state + draw with the share of each; free mode holds keys)")
    return serial_ratios()


if __name__ == "__main__":
    main()
