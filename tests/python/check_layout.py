"""check_layout.py LAYOUT_BINARY LIB_PY: every ctypes structure of
python/oit/_lib.py against the C compiler's layout of the same structure
(struct_layout.c): the same size, and each field at the same offset; and
its constants and spelt enums (ENUMS) against the C values, every value of
a spelt enum spelt. A structure reordered or a value renumbered in
include/oit/ and not in _lib.py reads garbage in Python without this.
Loads _lib.py by path: no numpy needed."""
import ctypes
import importlib.util
import subprocess
import sys

layout, enums = {}, {}
for line in subprocess.run([sys.argv[1]], check=True, capture_output=True,
                           text=True).stdout.splitlines():
    key, *rest = line.split()
    if key == "enum":
        enums[rest[0]] = int(rest[1])
        continue
    layout[key if not rest[0] == "size" else key + " size"] = int(rest[-1])

spec = importlib.util.spec_from_file_location("oit_lib", sys.argv[2])
lib = importlib.util.module_from_spec(spec)
spec.loader.exec_module(lib)

bad = []
structs = sorted({k.split()[0].split(".")[0] for k in layout})
for name in structs:
    cls = getattr(lib, name, None)
    if cls is None:
        bad.append("%s: not declared in _lib.py" % name)
        continue
    if ctypes.sizeof(cls) != layout[name + " size"]:
        bad.append("%s: %d bytes in ctypes, %d in C" % (name, ctypes.sizeof(cls),
                                                        layout[name + " size"]))
    for field, _ in cls._fields_:
        key = name + "." + field
        if key not in layout:
            bad.append("%s: C has no such field (or struct_layout.c misses it)" % key)
        elif getattr(cls, field).offset != layout[key]:
            bad.append("%s: offset %d in ctypes, %d in C" % (key, getattr(cls, field).offset,
                                                             layout[key]))
    declared = {f for f, _ in cls._fields_}
    for key in layout:
        if key.startswith(name + ".") and key.split(".", 1)[1] not in declared:
            bad.append("%s: in C, not in _lib.py" % key)
for name, value in enums.items():  # module-level constants: RENDER_TRANSLUCENT
    if hasattr(lib, name[4:]) and getattr(lib, name[4:]) != value:
        bad.append("%s: %r in _lib.py, %d in C" % (name, getattr(lib, name[4:]), value))
for table, prefix in lib.ENUMS.items():
    spelt = getattr(lib, table)
    for word, value in spelt.items():
        cname = prefix + word.upper().replace("-", "")
        if enums.get(cname) != value:
            bad.append("%s[%r] = %d: C's %s is %s" % (table, word, value, cname,
                                                    enums.get(cname)))
    for cname, value in enums.items():
        if cname.startswith(prefix) and value not in spelt.values():
            bad.append("%s = %d: no spelling in _lib.py's %s" % (cname, value, table))
checked = sum(1 for n in enums if hasattr(lib, n[4:])) + sum(len(getattr(lib, t))
                                                              for t in lib.ENUMS)
for b in bad:
    print("FAIL", b)
print("%d structures, %d fields, %d constants: %s" % (
    len(structs), sum(1 for k in layout if "." in k), checked,
    "ok" if not bad else "%d wrong" % len(bad)))
sys.exit(1 if bad else 0)
