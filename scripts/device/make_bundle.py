#!/usr/bin/env python3
"""Build .gpu/lib (+ .gpu/glibc) for the binaries named on the command line.

Libraries whose code the tests and the bench run are copied as they are; the
heavy ones that Debian's OpenCV only links for codecs, video and GUI (GDAL,
FFmpeg, GStreamer, Qt, ...) are replaced by stubs: a library with the same
SONAME, version definitions and the symbols that the loaded files refer to,
whose functions return 0 (and print their name to stderr on the first call:
OpenCV's static initialisers call a few, e.g. Qt's QWaitCondition, OpenEXR's
Chromaticities). OpenCV is linked -z now, so every symbol
must resolve at load time, which the stubs satisfy.
"""
import os, re, shutil, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
GPU = os.path.join(os.path.dirname(os.path.dirname(HERE)), ".gpu")  # scripts/device/ -> repo/.gpu
LIB = os.path.join(GPU, "lib")
GLIBC = os.path.join(GPU, "glibc")

GLIBC_NAMES = {"ld-linux-x86-64.so.2", "libc.so.6", "libm.so.6", "libpthread.so.0",
               "libdl.so.2", "librt.so.1", "libresolv.so.2", "libmvec.so.1"}
KEEP = [r"libopencv_.*", r"libz\.so\..*", r"libjpeg\.so\..*", r"libpng16\.so\..*",
        r"libwebp\.so\..*", r"libsharpyuv\.so\..*", r"liblapack\.so\..*", r"libblas\.so\..*",
        r"libgfortran\.so\..*", r"libquadmath\.so\..*", r"libtbb\.so\..*", r"libtbbmalloc\.so\..*",
        r"libprotobuf\.so\..*", r"libOpenCL\.so\..*", r"libbenchmark\.so\..*",
        r"libstdc\+\+\.so\..*", r"libgcc_s\.so\..*", r"libgomp\.so\..*"]


def needed(path):
    out = subprocess.run(["readelf", "-d", "-W", path], capture_output=True, text=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", out)


def resolve_map(binaries):
    m = {}
    for b in binaries:
        out = subprocess.run(["ldd", b], capture_output=True, text=True).stdout
        for line in out.splitlines():
            mm = re.match(r"\s*(\S+) => (/\S+)", line)
            if mm:
                m.setdefault(mm.group(1), mm.group(2))
            mm = re.match(r"\s*(/\S*ld-linux-x86-64\.so\.2)", line)
            if mm:
                m.setdefault("ld-linux-x86-64.so.2", mm.group(1))
    return m


def undefined(path):
    out = subprocess.run(["readelf", "--dyn-syms", "-W", path], capture_output=True,
                         text=True).stdout
    names = set()
    for line in out.splitlines():
        f = line.split()
        if len(f) >= 8 and f[0].endswith(":") and f[6] == "UND":
            names.add(f[7].split("@")[0])
    return names


def make_stub(soname, real, dest, wanted):
    syms = subprocess.run(["readelf", "--dyn-syms", "-W", real], capture_output=True,
                          text=True).stdout
    vd = subprocess.run(["readelf", "-V", "-W", real], capture_output=True, text=True).stdout
    versions = []
    sect = vd.split("Version needs section")[0]
    for flags, name in re.findall(r"Flags: (\S+)\s+Index: \d+\s+Cnt: \d+\s+Name: (\S+)", sect):
        if flags != "BASE" and name not in versions:
            versions.append(name)
    asm = [".text"]
    flags = [".bss"]
    data = [".data"]
    strs = [".section .rodata"]
    seen = set()
    n = 0
    for line in syms.splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(":") or f[6] in ("UND", "ABS"):
            continue
        typ, bind, name = f[3], f[4], f[7]
        if bind not in ("GLOBAL", "WEAK") or name in seen:
            continue
        seen.add(name)
        base, ver, default = name, None, True
        if "@@" in name:
            base, ver = name.split("@@")
        elif "@" in name:
            base, ver = name.split("@")
            default = False
        if base not in wanted:
            continue  # nothing loaded refers to it
        if ver is not None and ver not in versions:
            continue  # the base version: exported unversioned below
        n += 1
        impl = base if ver is None else f"__stub_{n}"
        size = int(f[2], 0) if f[2].isdigit() else int(f[2], 16) if f[2].startswith("0x") else 0
        if typ == "TLS":
            continue  # none of the stubbed libraries export thread-locals we need
        if typ in ("OBJECT", "COMMON"):
            data += [f"  .globl {impl}",
                     f"  .type {impl}, @object", f"  .size {impl}, {max(size, 1)}",
                     "  .p2align 4", f"{impl}:", f"  .zero {max(size, 1)}"]
        else:
            msg = f"[bundle] stub called (returns 0): {soname}: {base}\\n"
            strs += [f".Ls{n}: .ascii \"{msg}\""]
            flags += [f".Lf{n}: .byte 0"]
            asm += [f"  .globl {impl}", f"  .type {impl}, @function", f"{impl}:",
                    f"  cmpb $0, .Lf{n}(%rip)", "  jne 1f", f"  movb $1, .Lf{n}(%rip)",
                    f"  lea .Ls{n}(%rip), %rsi", f"  mov ${len(msg) - 1}, %edx",
                    "  mov $2, %edi", "  mov $1, %eax", "  syscall",
                    "1:", "  xor %eax, %eax", "  xor %edx, %edx", "  xorps %xmm0, %xmm0",
                    "  ret"]
        if ver is not None:
            sect_lines = data if typ in ("OBJECT", "COMMON") else asm
            sect_lines.append(f"  .symver {impl}, {base}{'@@' if default else '@'}{ver}")
    with tempfile.TemporaryDirectory() as tmp:
        s = os.path.join(tmp, "stub.s")
        with open(s, "w") as fh:
            fh.write("\n".join(asm + data + flags + strs) + "\n")
        cmd = ["gcc", "-shared", "-nostdlib", "-o", dest, s, f"-Wl,-soname,{soname}",
               "-Wl,-z,noexecstack"]
        if versions:
            vs = os.path.join(tmp, "v.map")
            with open(vs, "w") as fh:
                fh.write("".join(f"{v} {{ }};\n" for v in versions))
            cmd.append(f"-Wl,--version-script={vs}")
        subprocess.run(cmd, check=True)
    return n


def main():
    binaries = sys.argv[1:]
    for d in (LIB, GLIBC):
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
    where = resolve_map(binaries)
    todo = [s for b in binaries for s in needed(b)]
    done = set()
    report = []
    stubs = []
    while todo:
        so = todo.pop()
        if so in done:
            continue
        done.add(so)
        real = where.get(so)
        if real is None:
            sys.exit(f"cannot resolve {so}")
        real = os.path.realpath(real)
        if so in GLIBC_NAMES:
            shutil.copy2(real, os.path.join(GLIBC, so))
            report.append(("glibc", so, os.path.getsize(real)))
            todo += needed(real)
        elif any(re.fullmatch(k, so) for k in KEEP):
            shutil.copy2(real, os.path.join(LIB, so))
            report.append(("real", so, os.path.getsize(real)))
            todo += needed(real)
        else:
            stubs.append((so, real))
    wanted = set()
    for f in binaries + [os.path.join(d, n) for d in (LIB, GLIBC) for n in os.listdir(d)]:
        wanted |= undefined(f)
    for so, real in stubs:
        dest = os.path.join(LIB, so)
        count = make_stub(so, real, dest, wanted)
        report.append((f"stub({count} syms)", so, os.path.getsize(dest)))
    # glibc's loader, always (the fallback runs through it)
    if "ld-linux-x86-64.so.2" not in done:
        shutil.copy2(os.path.realpath(where["ld-linux-x86-64.so.2"]),
                     os.path.join(GLIBC, "ld-linux-x86-64.so.2"))
    for kind, so, size in sorted(report, key=lambda r: -r[2]):
        print(f"{kind:18s} {size:>10d} {so}")


main()
