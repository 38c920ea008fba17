# gdb pretty-printer for b-script's registered classes (bsc -g).
#
# A class registered from C++ shows in DWARF with its fields (.var) as data
# members. Its properties (.prop: a getter thunk, maybe a setter) have no
# place in the object, so gdb alone prints Eigen's Vector2f, registered with
# .prop<bs::mut(&Vector2f::x)>, as `{<No data fields>}`. bsc describes them
# twice (lib/CodeGen/CGDebugInfo.cpp, addProperties):
#   - each property with a scalar value is a member function whose linkage
#     name is its getter thunk: `print v.x()` calls the getter;
#   - the nested union `T::__bs_properties` lists every property with its
#     type: gdb's Python API cannot list a type's member functions.
# This printer prints a value of such a class as its data members followed
# by its properties, `{x = 1.5, y = -2}`, calling each getter in the
# inferior. Where a getter cannot be called it prints the members and
# `<not read: REASON>` for the property: no live process (a core file, or
# before `run`), a value gdb does not have in memory, a class-valued
# property (its getter returns through an out pointer), or a getter that
# fails; a getter that gets a signal is unwound (`set unwindonsignal`
# is on for the call), so the session goes on where it was.
#
# Load it with
#   source PREFIX/share/bscript/gdb/bscript_printers.py
# (in ~/.gdbinit, or `gdb -x ...`); docs/repl.md, "gdb: -g". `print/r`
# prints without it; `disable pretty-printer global bscript` turns it off.

import gdb
import gdb.printing

PROPERTIES = "__bs_properties"
# A convenience variable holding the object's address while a getter runs.
SELF = "__bs_self"


class Unreadable(Exception):
    pass


def _is_live():
    """Whether functions can be called: a running process, not a core file."""
    inferior = gdb.selected_inferior()
    if inferior is None or inferior.pid == 0:
        return False
    thread = gdb.selected_thread()
    if thread is None or not thread.is_valid() or thread.is_exited():
        return False
    connection = getattr(inferior, "connection", None)
    if connection is not None and connection.type == "core":
        return False
    return True


def _call_getter(address, name):
    """Calls property `name`'s getter on the object at `address`."""
    old = gdb.parameter("unwindonsignal")
    gdb.execute("set unwindonsignal on", to_string=True)
    try:
        gdb.set_convenience_variable(SELF, address)
        try:
            value = gdb.parse_and_eval("$%s->%s()" % (SELF, name))
            value.fetch_lazy()
            return value
        except gdb.error as e:
            # gdb has already reported the signal and where it came from.
            raise Unreadable("the getter got a signal" if "signaled" in str(e)
                             else "the getter failed: " + _reason(e))
    finally:
        gdb.set_convenience_variable(SELF, None)
        gdb.execute("set unwindonsignal %s" % ("on" if old else "off"),
                    to_string=True)


def _reason(error):
    """The first line of gdb's message, without its final period."""
    text = str(error).strip().splitlines()
    return text[0].rstrip(".") if text else "error"


class RegisteredClassPrinter:
    """A registered class: its data members, then its properties."""

    def __init__(self, value, properties):
        self.value = value
        self.properties = properties

    def _property(self, name, type):
        if type.strip_typedefs().code in (gdb.TYPE_CODE_STRUCT,
                                          gdb.TYPE_CODE_UNION):
            raise Unreadable("a class-valued property")
        address = self.value.address
        if address is None:
            raise Unreadable("not in memory")
        if not _is_live():
            raise Unreadable("no live process")
        return _call_getter(address, name)

    def children(self):
        # Evaluated here, not lazily: a getter must run before gdb prints
        # another value whose printer calls one.
        out = []
        for field in self.value.type.strip_typedefs().fields():
            if field.is_base_class or field.artificial or \
                    not hasattr(field, "bitpos") or not field.name:
                continue
            out.append((field.name, self.value[field]))
        for name, type in self.properties:
            try:
                out.append((name, self._property(name, type)))
            except Unreadable as e:
                out.append((name, "<not read: %s>" % e))
        return out


class BscriptPrinter(gdb.printing.PrettyPrinter):
    """Values of classes bsc's DWARF gives a __bs_properties union."""

    def __init__(self):
        super().__init__("bscript")
        self.cache = {}  # Struct name -> [(property, type)] or None.

    def _properties(self, type):
        name = type.name or type.tag
        if not name:
            return None
        if name not in self.cache:
            listed = None
            try:
                listed = gdb.lookup_type(name + "::" + PROPERTIES)
            except gdb.error:
                pass
            self.cache[name] = (
                [(f.name, f.type) for f in listed.fields()] if listed else None)
        return self.cache[name]

    def __call__(self, value):
        if not self.enabled:
            return None
        type = value.type.strip_typedefs().unqualified()
        if type.code != gdb.TYPE_CODE_STRUCT:
            return None
        properties = self._properties(type)
        if not properties:
            return None
        return RegisteredClassPrinter(value, properties)


def _new_objfile(event):
    # A JIT-registered object or a new program may define a type of a name
    # seen before without properties.
    _printer.cache.clear()


_printer = BscriptPrinter()
gdb.printing.register_pretty_printer(None, _printer, replace=True)
gdb.events.new_objfile.connect(_new_objfile)
