"""Used by shared-library.test: damage_elf.py IN OUT SECTION writes IN with
SECTION's sh_offset moved past the end of the file, as a truncated or
damaged download would leave it (the section header table stays intact)."""
import struct
import sys

data = bytearray(open(sys.argv[1], 'rb').read())
is64 = data[4] == 2
if is64:
    shoff, = struct.unpack_from('<Q', data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from('<HHH', data, 0x3a)
else:
    shoff, = struct.unpack_from('<I', data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from('<HHH', data, 0x2e)

def header(i):
    """(sh_name, sh_offset, position of sh_offset) of section i."""
    base = shoff + i * shentsize
    if is64:
        name, = struct.unpack_from('<I', data, base)
        off, = struct.unpack_from('<Q', data, base + 0x18)
        return name, off, base + 0x18
    name, = struct.unpack_from('<I', data, base)
    off, = struct.unpack_from('<I', data, base + 0x10)
    return name, off, base + 0x10

strtab = header(shstrndx)[1]
for i in range(shnum):
    name, _, pos = header(i)
    end = data.index(0, strtab + name)
    if data[strtab + name:end].decode() == sys.argv[3]:
        struct.pack_into('<Q' if is64 else '<I', data, pos, len(data) + 0x1000)
        break
else:
    sys.exit('no section ' + sys.argv[3])
open(sys.argv[2], 'wb').write(data)
