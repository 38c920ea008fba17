"""A reader of binary logs written from docs/repl.md ("The robot's log"),
apart from bsc's, for flight-recorder.test:

  bslog.py summary LOG            the header, and per block its codec and
                                  its cycles; the totals
  bslog.py damage LOG OUT CYCLE WHAT
                                  LOG with one byte of cycle CYCLE's WHAT
                                  (trace, output) flipped (raw blocks only)
  bslog.py cut LOG OUT BYTES      the first BYTES bytes of LOG
  bslog.py relayout LOG OUT       LOG with another layout in its header, as
                                  a target with other offsets would write
  bslog.py same A.jsonl B.jsonl   whether two recordings hold the same
                                  lines but for `tasks` (which only a
                                  replay computes), where A's calls may
                                  write more bytes than B's (the robot's
                                  recorder writes whole words) but every
                                  byte B's write, the same
"""
import struct
import sys

MAGIC = b"BSLOG\x1a"


class Reader:
    def __init__(self, data, at=0):
        self.data, self.at = data, at

    def uleb(self):
        value, shift = 0, 0
        while True:
            b = self.data[self.at]
            self.at += 1
            value |= (b & 0x7F) << shift
            shift += 7
            if not b & 0x80:
                return value

    def bytes(self, n):
        b = self.data[self.at:self.at + n]
        assert len(b) == n, "cut off"
        self.at += n
        return b

    def text(self):
        return self.bytes(self.uleb()).decode()

    def runs(self):
        count, at, out = self.uleb(), 0, []
        for _ in range(count):
            at += self.uleb()
            n = self.uleb()
            out.append((at, self.bytes(n)))
            at += n
        return out


def blocks(data):
    assert data[:6] == MAGIC, "not a log"
    assert struct.unpack_from("<H", data, 6)[0] == 1, "not format 1"
    at = 8
    while at < len(data):
        stored, raw, codec = struct.unpack_from("<IIB", data, at)
        body = data[at + 12:at + 12 + stored]
        assert len(body) == stored, "cut off block"
        if codec == 1:
            import zstandard  # Not needed by the tests: they read raw logs.
            body = zstandard.ZstdDecompressor().decompress(body, raw)
        yield at, codec, body
        at += 12 + stored


def records(data, header):
    """Yields (block, kind, fields, places) per record; `places` maps a
    part of a cycle record to the file offset of its bytes (raw blocks)."""
    for block_at, codec, body in blocks(data):
        r = Reader(body)
        while r.at < len(body):
            start = r.at
            tag = chr(body[r.at])
            r.at += 1
            if tag == "H":
                header.update(behavior=r.text(), entry=r.text(),
                              target=r.text(), layout=r.text(),
                              state=r.uleb(), input=r.uleb(),
                              output=r.uleb(), robots=r.uleb())
                header["sites"] = [r.text() for _ in range(r.uleb())]
                header["assertions"] = r.uleb()
                yield block_at, "H", None, None
            elif tag == "S":
                header["sites"] += [r.text() for _ in range(r.uleb())]
            elif tag == "G":
                yield block_at, "G", (r.uleb(), r.uleb(), r.uleb()), None
            elif tag == "C":
                robot, cycle, flags = r.uleb(), r.uleb(), r.bytes(1)[0]
                key = flags & 1
                for size in (header["input"], header["output"]):
                    if key:  # The input, then the output the entry found.
                        r.bytes(size)
                    else:
                        r.runs()
                calls = r.uleb()
                r.bytes(r.uleb())
                output_at = block_at + 12 + r.at
                if key:
                    r.bytes(header["output"])
                else:
                    r.runs()
                trace_at = None
                if flags & 2:
                    n = r.uleb()
                    trace_at = block_at + 12 + r.at
                    r.bytes(n)
                yield block_at, "C", (robot, cycle, key, calls), {
                    "output": output_at, "trace": trace_at,
                    "codec": codec}
            else:
                raise AssertionError("unknown record %r at %d" % (tag, start))


def summary(path):
    data = open(path, "rb").read()
    header = {}
    cycles, keys, calls, gaps, block_list = 0, 0, 0, [], set()
    for block_at, kind, fields, _ in records(data, header):
        block_list.add(block_at)
        if kind == "C":
            cycles += 1
            keys += fields[2]
            calls += fields[3]
        elif kind == "G":
            gaps.append(fields)
    print("entry %s target %s input %d output %d state %d robots %d" % (
        header["entry"], header["target"], header["input"],
        header["output"], header["state"], header["robots"]))
    print("sites %s" % ", ".join(header["sites"]))
    print("blocks %d cycles %d key %d calls %d lost %s" % (
        len(block_list), cycles, keys, calls, gaps or "none"))


def damage(path, out, cycle, what):
    data = bytearray(open(path, "rb").read())
    for _, kind, fields, places in records(bytes(data), {}):
        if kind == "C" and fields[1] == int(cycle):
            assert places["codec"] == 0, "a compressed block"
            data[places[what]] ^= 0x01
            break
    else:
        raise AssertionError("no cycle %s" % cycle)
    open(out, "wb").write(data)


def written_bytes(call):
    """{(block, offset): byte} of a call's `writes`."""
    out = {}
    for block, offset, hex_bytes in call.pop("writes", []):
        for i, b in enumerate(bytes.fromhex(hex_bytes)):
            out[(block, offset + i)] = b
    return out


def same(path_a, path_b):
    import json
    a, b = ([json.loads(l) for l in open(p) if l.strip()]
            for p in (path_a, path_b))
    if len(a) != len(b):
        raise SystemExit("%d lines against %d" % (len(a), len(b)))
    for n, (x, y) in enumerate(zip(a, b)):
        x.pop("tasks", None)
        y.pop("tasks", None)
        for cx, cy in zip(x.get("calls", []), y.get("calls", [])):
            wx, wy = written_bytes(cx), written_bytes(cy)
            if any(wx.get(k) != v for k, v in wy.items()):
                raise SystemExit("line %d: call %s writes otherwise" % (
                    n + 1, cx["fn"]))
        if x != y:
            raise SystemExit("line %d differs:\n%s\n%s" % (n + 1, x, y))
    print("the same %d lines" % len(a))


if __name__ == "__main__":
    command = sys.argv[1]
    if command == "summary":
        summary(sys.argv[2])
    elif command == "damage":
        damage(*sys.argv[2:6])
    elif command == "relayout":
        data = bytearray(open(sys.argv[2], "rb").read())
        header = {}
        next(records(bytes(data), header))
        at = data.index(header["layout"].encode())
        data[at] = ord("0") if data[at] != ord("0") else ord("1")
        open(sys.argv[3], "wb").write(data)
    elif command == "same":
        same(sys.argv[2], sys.argv[3])
    elif command == "cut":
        data = open(sys.argv[2], "rb").read()
        open(sys.argv[3], "wb").write(data[:int(sys.argv[4])])
