"""The expected output of examples/robot, from a model written from the
rules alone: docs/language.md's task semantics applied to the behaviors of
examples/robot/behaviors, and the world of examples/robot/robot/main.cpp.
Every value is a multiple of 0.25, so floats are exact."""

NEAR = 0.75
CYCLES = 30


def dist_sq(a, b):
    return (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2


def approach(self_pos, p):
    """One call of skills::approach: the loop condition is tested at the
    top and after every yield, so each call walks (running) or stands
    (done). Returns (motion, target, done)."""
    if dist_sq(self_pos, p) > NEAR * NEAR:
        return "walk", p, False
    return "stand", None, True


def step(frm, to):
    d = to - frm
    return frm + max(-0.5, min(0.5, d))


def fmt(v):
    return "%g" % v


def main():
    ball = (3.0, 1.0)
    striker, keeper = (0.0, 0.0), (-4.5, 0.0)
    s_out = {"motion": "stand", "target": (0.0, 0.0)}
    k_out = {"motion": "stand", "target": (0.0, 0.0)}
    kicks = 0
    for cycle in range(1, CYCLES + 1):
        motion, target, done = approach(striker, ball)
        s_out["motion"] = motion
        if target is not None:
            s_out["target"] = target
        if done:
            s_out["motion"] = "kick"
        motion, target, _ = approach(keeper, (-4.5, ball[1]))
        k_out["motion"] = motion
        if target is not None:
            k_out["target"] = target
        for pos_name, out in (("striker", s_out), ("keeper", k_out)):
            if out["motion"] == "walk":
                pos = striker if pos_name == "striker" else keeper
                pos = (step(pos[0], out["target"][0]),
                       step(pos[1], out["target"][1]))
                if pos_name == "striker":
                    striker = pos
                else:
                    keeper = pos
        if s_out["motion"] == "kick":
            ball = (ball[0] + 2, ball[1] - 0.5)
            kicks += 1
            print("cycle %d: kick from (%s, %s), ball now at (%s, %s)"
                  % (cycle, fmt(striker[0]), fmt(striker[1]),
                     fmt(ball[0]), fmt(ball[1])))
    print("after %d cycles: %d kicks, striker at (%s, %s), keeper at (%s, %s)"
          % (CYCLES, kicks, fmt(striker[0]), fmt(striker[1]),
             fmt(keeper[0]), fmt(keeper[1])))


main()
