"""Writes and compares the REPL sessions of test/REPL/boundary.test.

  sessions.py write N DIR [ROBOT]
      DIR/live.txt steps N cycles one at a time; DIR/travel.txt runs N
      cycles, then goes to every cycle (forwards, then backwards with
      :back) and asks the same questions there. With ROBOT (a session of
      `--robots`), both ask robot ROBOT (`:robot`), and the travel leaves
      out the :until, whose cycle is the one robot's.
  sessions.py compare LIVE.out TRAVEL.out
      Every answer of the travel session about cycle c equals the live
      session's about cycle c; its :history lines equal the changes of the
      live values.
Each block of answers starts with a marker, the value 1000000 + c.
"""
import re
import sys

QUESTIONS = ["Game::striker.state", "Game::striker.since",
             "Game::striker.draws", "input.time", "input.gameState",
             "input.ballX", "input.button", "output.motion", "output.speed",
             "output.headMode", ":why striker", ":why head"]
HISTORY = ["Game::striker.state", "input.gameState", "output.speed"]


def ask(c):
    return "%d + %d\n" % (1000000, c) + "".join(q + "\n" for q in QUESTIONS)


def write(n, out, robot=None):
    start = ":robot %d\n" % robot if robot is not None else ""
    with open(out + "/live.txt", "w") as f:
        f.write(start + ask(0))
        for c in range(1, n + 1):
            f.write(":step\n" + ask(c))
    with open(out + "/travel.txt", "w") as f:
        f.write(start + ":run %d\n" % n)
        for q in HISTORY:
            f.write(":history %s\n" % q)
        for c in range(1, n + 1):
            f.write(":goto %d\n" % c + ask(c))
        f.write(":goto %d\n" % n)
        for c in range(n - 1, 0, -1):
            f.write(":back\n" + ask(c))
        # :until and :run in the past re-run the history too.
        if robot is None:
            f.write(":goto 1\n:until Game::striker.state == 3\n" + ask(14))
        f.write(":goto 2\n:run 5\n" + ask(7))


def blocks(path):
    """The answers after each marker, by cycle (a list per visit), and the
    lines before the first marker."""
    text = open(path).read().splitlines()
    found, head, cur = {}, [], None
    for line in text:
        m = re.fullmatch(r"\(int\) 10(\d{5})", line)
        if m:
            cur = []
            found.setdefault(int(m.group(1)), []).append(cur)
        elif cur is None:
            head.append(line)
        elif not re.match(r"cycle \d+(, robot \d+)?: (output|game \[)"
                          r"|stopped |ran |robot \d+ of ", line):
            cur.append(line)
    return found, head


def compare(live_path, travel_path):
    live, _ = blocks(live_path)
    travel, head = blocks(travel_path)
    bad = 0
    for c, visits in sorted(travel.items()):
        for v in visits:
            if v != live[c][0]:
                bad += 1
                print("cycle %d differs:\n  live: %s\n  travel: %s" %
                      (c, live[c][0], v))
    # The :history answers against the live values, from cycle 0 on.
    wanted = []
    for q in HISTORY:
        values = [live[c][0][QUESTIONS.index(q)].split(") ", 1)[1]
                  for c in sorted(live)]
        wanted += ["cycle %d: %s -> %s" % (c + 1, values[c], values[c + 1])
                   for c in range(len(values) - 1)
                   if values[c] != values[c + 1]]
    got = [l for l in head if re.match(r"cycle \d+: .* -> ", l)]
    if got != wanted:
        bad += 1
        print("history differs:\n  live: %s\n  travel: %s" % (wanted, got))
    visits = sum(len(v) for v in travel.values())
    print("%d visits of %d cycles, %d differ" % (visits, len(travel), bad))
    return 1 if bad or not visits else 0


if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(int(sys.argv[2]), sys.argv[3],
              int(sys.argv[4]) if len(sys.argv) > 4 else None)
    else:
        sys.exit(compare(sys.argv[2], sys.argv[3]))
