#!/usr/bin/env python3
"""Runs bsc over binding objects with damaged section headers.

"A damaged binding object gets a clear error, never a crash or a hang"
(issue 14): llvm::object trusts section headers, so bsc must check them
before it walks symbols and relocations. This patches the section header
fields of a real binding object (ELF32 or ELF64, relocatable or shared
library) and runs bsc on each variant with a time limit.

  write OBJ OUTDIR
      writes the named variants of OBJ (OUTDIR/<case>.<o|so>) and prints
      "<case> <file> <expected message>" per line, for FileCheck tests
  check BSC OBJ --cmd ARGS [--cmd ARGS...]
      runs every named variant through each command ({obj} stands for the
      file): each must exit 1 with `bsc: error: FILE: damaged ...: <the
      expected message>`. The undamaged object must exit 0 (a positive
      control: the commands do work).
  fuzz BSC OBJ --cmd ARGS [--cmd ARGS...]
      sets each field (sh_type, sh_offset, sh_size, sh_entsize, sh_link,
      sh_info, sh_addralign) of each section header, one at a time, to a
      few nasty values; every run must exit 0 or 1 (1 with an error
      message) without "LLVM ERROR".

Every run must end within --timeout seconds (lit's own timeout is not per
test). Prints one line per failure and a summary; exits 1 on any failure.
"""
import argparse
import concurrent.futures
import os
import re
import shlex
import struct
import subprocess
import sys
import tempfile

SHT_PROGBITS, SHT_SYMTAB, SHT_STRTAB, SHT_RELA = 1, 2, 3, 4
SHT_NOBITS, SHT_REL, SHT_DYNSYM, SHT_RELR = 8, 9, 11, 19
SHT_CREL = 0x40000014

# Field -> (offset, format) in ELF32 and ELF64 section headers.
FIELDS32 = {'sh_name': (0, 'I'), 'sh_type': (4, 'I'), 'sh_offset': (16, 'I'),
            'sh_size': (20, 'I'), 'sh_link': (24, 'I'), 'sh_info': (28, 'I'),
            'sh_addralign': (32, 'I'), 'sh_entsize': (36, 'I')}
FIELDS64 = {'sh_name': (0, 'I'), 'sh_type': (4, 'I'), 'sh_offset': (24, 'Q'),
            'sh_size': (32, 'Q'), 'sh_link': (40, 'I'), 'sh_info': (44, 'I'),
            'sh_addralign': (48, 'Q'), 'sh_entsize': (56, 'Q')}
FUZZED = ['sh_type', 'sh_offset', 'sh_size', 'sh_entsize', 'sh_link',
          'sh_info', 'sh_addralign']


class Elf:
    """The section headers of a little-endian ELF file."""

    def __init__(self, data):
        if data[:4] != b'\x7fELF' or data[5] != 1:
            sys.exit('not a little-endian ELF file')
        self.data = bytes(data)
        self.is64 = data[4] == 2
        if self.is64:
            self.type, = struct.unpack_from('<H', data, 16)
            self.shoff, = struct.unpack_from('<Q', data, 0x28)
            self.shentsize, self.shnum, shstrndx = struct.unpack_from('<HHH', data, 0x3a)
        else:
            self.type, = struct.unpack_from('<H', data, 16)
            self.shoff, = struct.unpack_from('<I', data, 0x20)
            self.shentsize, self.shnum, shstrndx = struct.unpack_from('<HHH', data, 0x2e)
        self.fields = FIELDS64 if self.is64 else FIELDS32
        strtab = self.get(shstrndx, 'sh_offset')
        self.names = []
        for i in range(self.shnum):
            start = strtab + self.get(i, 'sh_name')
            self.names.append(data[start:data.index(0, start)].decode())
        self.kind = 'shared library' if self.type == 3 else 'object'
        self.ext = 'so' if self.type == 3 else 'o'

    def pos(self, i, field):
        off, fmt = self.fields[field]
        return self.shoff + i * self.shentsize + off, '<' + fmt

    def get(self, i, field):
        pos, fmt = self.pos(i, field)
        return struct.unpack_from(fmt, self.data, pos)[0]

    def patched(self, i, field, value):
        """The file with `field` of section `i` set to `value`."""
        pos, fmt = self.pos(i, field)
        out = bytearray(self.data)
        struct.pack_into(fmt, out, pos, value & (0xffffffffffffffff if fmt == '<Q' else 0xffffffff))
        return bytes(out)

    def find(self, pred):
        for i in range(1, self.shnum):
            if pred(i):
                return i
        return None

    def by_name(self, name):
        return self.find(lambda i: self.names[i] == name)


def cases(elf):
    """The named variants: (case, bytes, expected message after
    `damaged <kind>: `)."""
    modules = elf.by_name('bs_modules')
    if elf.kind == 'object':
        rel = elf.find(lambda i: elf.get(i, 'sh_type') in (SHT_REL, SHT_RELA)
                       and elf.get(i, 'sh_info') == modules)
    else:
        rel = elf.find(lambda i: elf.names[i] in ('.rela.dyn', '.rel.dyn'))
    symtab = elf.by_name('.symtab')
    dynsym = elf.by_name('.dynsym')
    if modules is None or rel is None or symtab is None:
        sys.exit('the object lacks bs_modules, its relocations or .symtab')
    rel_name = elf.names[rel]
    rel_entsize = elf.get(rel, 'sh_entsize')
    sym_entsize = 24 if elf.is64 else 16
    # A size no file has, a whole number of symbols (so that only the
    # file size can refuse it; the reader used to walk it).
    huge = sym_entsize * (1 << 58) if elf.is64 else 0x7ffffff0
    out = [
        ('reloc-entsize-0', elf.patched(rel, 'sh_entsize', 0),
         f"relocation section '{rel_name}': section [index {rel}] has "
         f"invalid sh_entsize: expected {rel_entsize}, but got 0"),
        ('reloc-size-odd', elf.patched(rel, 'sh_size', elf.get(rel, 'sh_size') - 1),
         f"relocation section '{rel_name}': section [index {rel}] has an "
         f"invalid sh_size ({elf.get(rel, 'sh_size') - 1}) which is not a "
         f"multiple of its sh_entsize ({rel_entsize})"),
        ('reloc-link-outside', elf.patched(rel, 'sh_link', elf.shnum + 7),
         f"relocation section '{rel_name}': section [index {rel}] has "
         f"sh_link {elf.shnum + 7}, which is not a section"),
        ('reloc-link-not-symtab', elf.patched(rel, 'sh_link', modules),
         f"relocation section '{rel_name}': section [index {rel}] has "
         f"sh_link {modules}, which is not a symbol table"),
        ('modules-rela', elf.patched(modules, 'sh_type', SHT_RELA),
         f"section 'bs_modules': section [index {modules}] has type "
         f"SHT_RELA (expected SHT_PROGBITS)"),
        ('symtab-entsize-0', elf.patched(symtab, 'sh_entsize', 0),
         f"symbol table '.symtab': section [index {symtab}] has invalid "
         f"sh_entsize: expected {sym_entsize}, but got 0"),
        ('symtab-huge', elf.patched(symtab, 'sh_size', huge),
         f"symbol table '.symtab': section [index {symtab}] has a sh_offset "
         f"(0x{elf.get(symtab, 'sh_offset'):x}) + sh_size (0x{huge:x}) that "
         f"is greater than the file size (0x{len(elf.data):x})"),
    ]
    text = elf.find(lambda i: elf.names[i].startswith('.text')
                    and elf.get(i, 'sh_size') > 0)
    bss = elf.find(lambda i: elf.get(i, 'sh_type') == SHT_NOBITS)
    if elf.kind == 'object' and bss is not None:
        out.append(('bss-huge', elf.patched(bss, 'sh_size', 0xffffffff),
                    f"section '{elf.names[bss]}': section [index {bss}] has "
                    f"sh_size 0xffffffff, more than bsc allows for zero-filled "
                    f"data (0x10000000)"))
    out += [
        ('text-nobits', elf.patched(text, 'sh_type', SHT_NOBITS),
         f"section '{elf.names[text]}': section [index {text}] holds code "
         f"but has type SHT_NOBITS"),
        ('text-at-0', elf.patched(text, 'sh_offset', 0),
         f"section '{elf.names[text]}': section [index {text}] overlaps "
         f"the ELF header or the section header table"),
        ('strtab-empty', elf.patched(elf.get(symtab, 'sh_link'), 'sh_size', 1),
         f"symbol table '.symtab': symbol 1 has its name outside the string "
         f"table"),
    ]
    if dynsym is not None:
        out.append(('dynsym-huge', elf.patched(dynsym, 'sh_size', huge),
                    f"symbol table '.dynsym': section [index {dynsym}] has a "
                    f"sh_offset (0x{elf.get(dynsym, 'sh_offset'):x}) + sh_size "
                    f"(0x{huge:x}) that is greater than the file size "
                    f"(0x{len(elf.data):x})"))
    return out


def fuzz_variants(elf):
    """(description, bytes) for each field of each section set to each
    nasty value."""
    size = len(elf.data)
    for i in range(1, elf.shnum):
        for field in FUZZED:
            orig = elf.get(i, field)
            values = [0, 1, 0xffffffff, size, orig ^ 1]
            if field == 'sh_type':
                values += [SHT_SYMTAB, SHT_RELA, SHT_NOBITS, SHT_REL,
                           SHT_DYNSYM, SHT_RELR, SHT_CREL]
            for v in dict.fromkeys(values):
                if v != orig:
                    yield (f'section {i} ({elf.names[i]}) {field}={v:#x}',
                           elf.patched(i, field, v))


def run(bsc, cmd, path, timeout):
    """(returncode or None on timeout, stderr)."""
    args = [bsc] + [a.replace('{obj}', path) for a in shlex.split(cmd)]
    try:
        p = subprocess.run(args, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, ''
    return p.returncode, p.stderr.decode(errors='replace')


# An error of bsc: `bsc: error:`, or one at a place in the script (a
# damaged object may read as one without the module the script requires).
DIAG_LINE = re.compile(r'^(bsc: error: |\S.*:\d+:\d+: error: )')


def judge(status, err, timeout):
    """Why a run is not an orderly end (exit 0, or 1 with `bsc: error:`),
    or None."""
    if status is None:
        return f'did not end within {timeout} s'
    if 'LLVM ERROR' in err:
        return 'LLVM ERROR\n' + err[-2000:]
    if status < 0:
        return f'killed by signal {-status}\n' + err[-2000:]
    if status not in (0, 1):
        return f'exit status {status}\n' + err[-2000:]
    if status == 1 and not any(DIAG_LINE.match(l) for l in err.splitlines()):
        return 'exit status 1 without a diagnostic\n' + err[-2000:]
    return None


def main():
    ap = argparse.ArgumentParser(
        description='Runs bsc over binding objects with damaged section headers.')
    ap.add_argument('mode', choices=['write', 'check', 'fuzz'])
    ap.add_argument('args', nargs='+', help='write: OBJ OUTDIR; check, fuzz: BSC OBJ')
    ap.add_argument('--cmd', action='append', default=[],
                    help='bsc arguments, {obj} for the damaged file')
    ap.add_argument('--timeout', type=float, default=10)
    ap.add_argument('--jobs', type=int, default=2)
    opts = ap.parse_args()
    if len(opts.args) != 2 or (opts.mode != 'write' and not opts.cmd):
        ap.print_usage(sys.stderr)
        return 2

    if opts.mode == 'write':
        obj, outdir = opts.args
        elf = Elf(open(obj, 'rb').read())
        os.makedirs(outdir, exist_ok=True)
        for name, data, expected in cases(elf):
            path = os.path.join(outdir, f'{name}.{elf.ext}')
            open(path, 'wb').write(data)
            print(name, path, f'damaged {elf.kind}: {expected}')
        return 0

    bsc, obj = opts.args
    elf = Elf(open(obj, 'rb').read())
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        # The positive control: every command works on the real object.
        for cmd in opts.cmd:
            status, err = run(bsc, cmd, obj, opts.timeout)
            if status != 0:
                print(f'FAIL: the undamaged {obj} with `{cmd}`: exit status {status}\n{err}')
                return 1
        if opts.mode == 'check':
            variants = [(n, d, e) for n, d, e in cases(elf)]
        else:
            variants = [(n, d, None) for n, d in fuzz_variants(elf)]
        jobs = []
        for k, (name, data, expected) in enumerate(variants):
            path = os.path.join(tmp, f'{k}.{elf.ext}')
            open(path, 'wb').write(data)
            for cmd in opts.cmd:
                jobs.append((name, path, expected, cmd))

        def one(job):
            name, path, expected, cmd = job
            status, err = run(bsc, cmd, path, opts.timeout)
            why = judge(status, err, opts.timeout)
            if why is None and expected is not None:
                want = f'bsc: error: {path}: damaged {elf.kind}: {expected}'
                if status != 1:
                    why = f'exit status {status}, expected 1'
                elif want not in err.splitlines():
                    why = f'expected the line\n  {want}\ngot\n{err[-2000:]}'
            return None if why is None else f'FAIL: {name} with `{cmd}`: {why}'

        with concurrent.futures.ThreadPoolExecutor(opts.jobs) as pool:
            failures = [f for f in pool.map(one, jobs) if f]
    for f in failures:
        print(f)
    print(f'{obj}: {len(jobs)} runs of {len(variants)} damaged variants, '
          f'{len(failures)} failed')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
