#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""tests/hlsl: the installed-style HLSL module share/emcv/emcv_port.hlsl (cmake/emcv_port_hlsl.cmake).

check_hlsl.py module   --module M --port-glsl G --glslang V --work W
    M is a library, not a kernel: include-guarded, no entry point, resource, cbuffer, register or global;
    every emcv_* function and Emcv* struct of emcv_port.glsl under the same name; glslang finds no `main` in it.
check_hlsl.py consumer --module M --consumer C --glslang V --spirv-cross X --work W
    C (tests/hlsl/consumer.comp.hlsl) #includes M, declares its own resources and compiles with glslang's HLSL
    front end: glslangValidator -D -V -e main -S comp -I<dir of M> C; its descriptors are C's own.
check_hlsl.py layout   --module M --port-glsl G --consumer C --host-layout H --glslang V --spirv-cross X --work W
    The Direct3D layouts of the port's structs (StructuredBuffer and cbuffer packing, computed from M's struct
    declarations by d3d_layout below, whose rules are checked against known Direct3D reflections first),
    pinned in D3D_EXPECTED, compared with emcv/port/host.hpp's std430 mirrors and the port's C++ structs (H
    prints them) and cross-checked by tools: glslang's scalar block layout (tight packing, as a Direct3D
    structured buffer) and spirv-cross's HLSL cbuffer packing check.
check_hlsl.py gpu-modules --modules-dir D --source-modules S --generator G --module M --cmake C --glslang V --work W
    D (share/emcv/module/hlsl) holds the HLSL version of every GPU module of S (shaders/module) and the language
    file: libraries, include-guarded, without entry point, resource or register; each is its GLSL module's code
    with only the #include lines rewritten (one implementation); together, after M, they compile with glslang's
    HLSL front end for every method, without an entry point or any emcv_app_* definition. G
    (cmake/emcv_module_hlsl.cmake) writes D's files from S as they are now, and refuses modules that hold each
    GLSL-only construct it names; the library check refuses a module with a resource, an entry point or no guard.
check_hlsl.py gpu-modules-consumer --modules-dir D --module M --port-glsl G --port-kernel K --port-script P
                                   --consumer-dir C --cmake X --glslang V --spirv-cross Y --work W
    C (tests/hlsl/modules) is an HLSL engine's side of the modules (app.hlsl: its own resources and emcv_app_*
    functions) and its passes: plan, solve, count, update (also with EMCV_ADAPTIVE_PLAN_NEXT) and quality. Each
    compiles with glslang's HLSL front end for every method, against M (the installed port: a quality target at
    K = 1) and against the port translated in budget mode (P with EMCV_HISTORY_SPP_BUDGET 8.0f) at K = 1, 2 and 4;
    its descriptors are C's own, and no bool vector is read where GLSL's scalar == would be (a vector compare in a
    module, which glslang narrows to its first component without a word).
Exit 0 pass, 1 fail, 77 skipped (a tool missing).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys


def fail(message):
    print(f"FAIL: {message}")
    sys.exit(1)


def run(command, expect_ok=True):
    result = subprocess.run(command, capture_output=True, text=True)
    output = result.stdout + result.stderr
    if expect_ok and result.returncode != 0:
        fail(f"{' '.join(command)} exited {result.returncode}:\n{output}")
    return result.returncode, output


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


# ---- Direct3D packing rules -------------------------------------------------------------------------------------
# A member type: ("scalar"|"vector", components) of 4-byte components, ("array", element, count) or
# ("struct", [(name, type), ...]). Only what the port's structs use (32-bit scalars and vectors, arrays, structs).

SCALARS = {"float", "uint", "int", "bool"}


def parse_type(text, count, structs):
    m = re.fullmatch(r"(float|uint|int|bool)([1-4]?)", text)
    if m:
        base = ("vector", int(m.group(2))) if m.group(2) else ("scalar", 1)
    elif text in structs:
        base = ("struct", structs[text])
    else:
        fail(f"d3d_layout: unsupported member type {text}")
    return ("array", base, count) if count is not None else base


def parse_structs(source):
    """struct Name { type member[N]; ... }; declarations of an HLSL source, in order."""
    structs = {}
    for name, body in re.findall(r"\nstruct (\w+)\s*\{([^}]*)\};", "\n" + source):
        members = []
        for line in body.split(";"):
            line = line.strip()
            if not line:
                continue
            m = re.fullmatch(r"(\w+)\s+(\w+)\s*(?:\[\s*(\d+)\s*\])?", line)
            if not m:
                fail(f"d3d_layout: cannot read member '{line}' of struct {name}")
            count = int(m.group(3)) if m.group(3) else None
            members.append((m.group(2), parse_type(m.group(1), count, structs)))
        structs[name] = members
    return structs


def sb_size(t):
    """Structured buffer (tight, C-like) packing: every 32-bit component 4-byte aligned, no padding."""
    kind = t[0]
    if kind in ("scalar", "vector"):
        return 4 * t[1]
    if kind == "array":
        return sb_size(t[1]) * t[2]
    return sum(sb_size(mt) for _, mt in t[1])


def sb_layout(members):
    offsets, offset = {}, 0
    for name, t in members:
        offsets[name] = offset
        offset += sb_size(t)
    return offsets, offset


def cb_place(t, offset):
    """cbuffer packing: 16-byte rows; a scalar or vector never straddles a row; a struct and an array start a
    row, each array element starts a row; the next member packs right after (into the last row's rest).
    Returns (offset of t, its size: unpadded, up to the end of its last component)."""
    kind = t[0]
    if kind in ("scalar", "vector"):
        size = 4 * t[1]
        if offset // 16 != (offset + size - 1) // 16:
            offset = (offset + 15) // 16 * 16
        return offset, size
    offset = (offset + 15) // 16 * 16
    if kind == "array":
        element = cb_size(t[1])
        stride = (element + 15) // 16 * 16
        return offset, stride * (t[2] - 1) + element
    return offset, cb_layout(t[1])[1]


def cb_size(t):
    return cb_place(t, 0)[1]


def cb_layout(members):
    offsets, offset = {}, 0
    for name, t in members:
        at, size = cb_place(t, offset)
        offsets[name] = at
        offset = at + size
    return offsets, offset


def check_rules():
    """The rules against Direct3D's own reflection of small cases (the offsets fxc/dxc report for them)."""
    structs = parse_structs("""
struct Inner { float b[2]; float2 c; float2 d; };
struct S { float2 a; Inner s; float e; };
struct Row { float x; float y[2]; float end; };
struct C { float dummy0; Row bar; float end; };
struct A { float2 arr2[3]; float3 arr3[3]; float s; };
struct V { float x; float3 v; float2 w; float2 straddle; float3 next; };
""")
    cases = [
        (sb_layout(structs["S"]), ({"a": 0, "s": 8, "e": 32}, 36)),
        (sb_layout(structs["Inner"]), ({"b": 0, "c": 8, "d": 16}, 24)),
        (cb_layout(structs["Row"]), ({"x": 0, "y": 16, "end": 36}, 40)),
        (cb_layout(structs["C"]), ({"dummy0": 0, "bar": 16, "end": 56}, 60)),
        (cb_layout(structs["A"]), ({"arr2": 0, "arr3": 48, "s": 92}, 96)),
        (cb_layout(structs["V"]), ({"x": 0, "v": 4, "w": 16, "straddle": 24, "next": 32}, 44)),
    ]
    for got, want in cases:
        if got != want:
            fail(f"d3d_layout's rules: got {got}, Direct3D gives {want}")


# The Direct3D layouts of the port's shared structs (byte offsets; size: a StructuredBuffer's element stride, a
# cbuffer member's unpadded size). A change of a struct in include/emcv/port changes them: update these, the
# module's header and docs/porting.md ("HLSL") together.
D3D_EXPECTED = {
    "structured": {
        "EmcvEmcm2": ({"mean": 0, "cov": 8, "count": 20, "rejected": 24, "reseeded": 28}, 32),
        "EmcvMovingStats": ({"mean": 0, "variance": 4, "count": 8, "rejected": 12, "reseeded": 16}, 20),
        "EmcvBudgetBlock": ({"lambda": 0, "planned": 4, "default_pixels": 8, "zero_pixels": 12, "solves": 16,
                             "bin_count": 20, "bin_fraction": 1044, "raw_count": 2068, "raw_inverse_frames": 3092,
                             "mean_sigma2": 3096, "between_variance": 3100}, 3104),
    },
    "cbuffer": {
        "EmcvEmcm2": ({"mean": 0, "cov": 16, "count": 28, "rejected": 32, "reseeded": 36}, 40),
        "EmcvMovingStats": ({"mean": 0, "variance": 4, "count": 8, "rejected": 12, "reseeded": 16}, 20),
        "EmcvBudgetBlock": ({"lambda": 0, "planned": 4, "default_pixels": 8, "zero_pixels": 12, "solves": 16,
                             "bin_count": 32, "bin_fraction": 4128, "raw_count": 8224, "raw_inverse_frames": 12308,
                             "mean_sigma2": 12312, "between_variance": 12316}, 12320),
    },
}


def reflect_types(spirv_cross, spv):
    """{type name: ({member: offset}, array stride of the last member or None)} from spirv-cross --reflect."""
    _, out = run([spirv_cross, spv, "--reflect"])
    types = {}
    for t in json.loads(out)["types"].values():
        types.setdefault(t["name"], []).append({m["name"]: m["offset"] for m in t["members"] if "offset" in m})
    return json.loads(out), types


def buffer_stride(reflection, block):
    """The element stride of the runtime array of a storage block (its one member)."""
    for t in reflection["types"].values():
        if t["name"] == block:
            return t["members"][0]["array_stride"]
    fail(f"no block {block} in the reflection")


# ---- the checks -------------------------------------------------------------------------------------------------

def check_module(args):
    module = read(args.module)
    glsl = read(args.port_glsl)
    code = re.sub(r"//[^\n]*", "", module)  # the header comment may name what the code must not hold
    for pattern, what in [(r"\bregister\s*\(", "a register"), (r"\bpackoffset\b", "a packoffset"),
                          (r"\bcbuffer\b|\btbuffer\b|\bConstantBuffer\b", "a constant buffer"),
                          (r"\b(RW)?(ByteAddress|Structured)Buffer\b|\b(RW)?Texture\w*\b|\bSamplerState\b",
                           "a resource"),
                          (r"\bnumthreads\b", "an entry point's [numthreads]"), (r"\bmain\s*\(", "a `main`"),
                          (r"\bcomp_main\b|\bSPIRV_Cross_Input\b|\bgl_\w+", "the reference kernel's code"),
                          (r"^static\s+(?!const\b)", "a mutable global")]:
        if re.search(pattern, code, re.MULTILINE):
            fail(f"{args.module} holds {what}: {re.search(pattern, code, re.MULTILINE).group(0)!r}")
    if not re.search(r"^#ifndef (\w+)\n#define \1\n", module, re.MULTILINE) or not module.rstrip().endswith("#endif  // EMCV_PORT_HLSL"):
        fail(f"{args.module} is not include-guarded")
    functions = sorted(set(re.findall(r"\n(?:EMCV_FN )?\w+ (emcv_[a-z0-9_]+)\(", glsl)))
    missing = [f for f in functions if not re.search(rf"\n\w+ {f}\(", module)]
    if missing:
        fail(f"{args.module} lacks the port functions {missing} (call them in shaders/reference/port_reference.glsl)")
    structs = sorted(set(re.findall(r"\nstruct (Emcv\w+)", glsl)))
    missing = [s for s in structs if f"\nstruct {s}\n" not in module]
    if missing:
        fail(f"{args.module} lacks the port structs {missing}")
    for name, value in re.findall(r"\n#ifndef (EMCV_[A-Z0-9_]+)\n#define \1 ([^\n/]+)", glsl):
        if not re.fullmatch(r"[-+(). 0-9eEuf]*[0-9][-+(). 0-9eEuf]*", value):
            continue  # a GLSL spelling (EMCV_PRECISE), not a number
        if f"//   {name} {value.strip()}\n" not in module:
            fail(f"{args.module}'s header does not state the tunable {name} (default {value.strip()})")
    # the module alone is no kernel: glslang finds no entry point in it
    os.makedirs(args.work, exist_ok=True)
    rc, out = run([args.glslang, "-D", "-V", "-e", "main", "-S", "comp", args.module,
                   "-o", os.path.join(args.work, "module_alone.spv")], expect_ok=False)
    if "Entry point not found" not in out:
        fail(f"glslang found an entry point `main` in {args.module} alone (exit {rc}):\n{out}")
    # a tunable #defined before the #include is refused, not silently ignored
    probe = os.path.join(args.work, "tunable_probe.comp.hlsl")
    with open(probe, "w", encoding="utf-8") as f:
        f.write(f'#define EMCV_HISTORY_ETA_EMCM 0.05f\n#include "{os.path.basename(args.module)}"\n'
                "[numthreads(1, 1, 1)] void main() {}\n")
    rc, out = run([args.glslang, "-D", "-V", "-e", "main", "-S", "comp",
                   "-I" + os.path.dirname(os.path.abspath(args.module)), probe, "-o",
                   os.path.join(args.work, "probe.spv")], expect_ok=False)
    if rc == 0 or "EMCV_HISTORY_ETA_EMCM" not in out:
        fail(f"a tunable #defined before the #include was not refused (exit {rc}):\n{out}")
    print(f"hlsl module: OK ({len(functions)} functions, {len(structs)} structs, no entry point or resource)")


def consumer_spv(args):
    os.makedirs(args.work, exist_ok=True)
    spv = os.path.join(args.work, "consumer.spv")
    # -V: glslang's HLSL front end only generates SPIR-V (without it: "HLSL requires SPIR-V code generation")
    run([args.glslang, "-D", "-V", "-e", "main", "-S", "comp", "-I" + os.path.dirname(os.path.abspath(args.module)),
         args.consumer, "-o", spv])
    return spv


def check_consumer(args):
    spv = consumer_spv(args)
    reflection, _ = reflect_types(args.spirv_cross, spv)
    names = sorted(r["name"] for kind in ("ssbos", "ubos", "images") for r in reflection.get(kind, []))
    want = sorted(["irradiance", "covariance", "residual", "budget", "Frame", "history_cov"])
    if names != want:
        fail(f"the consumer's descriptors are {names}, not its own {want}")
    print(f"hlsl consumer: OK (descriptors {', '.join(names)})")


def check_layout(args):
    check_rules()
    structs = parse_structs(read(args.module))
    _, out = run([args.host_layout])
    host = json.loads(out)
    rows = []
    for name in ("EmcvEmcm2", "EmcvMovingStats", "EmcvBudgetBlock"):
        if name not in structs:
            fail(f"{args.module} declares no struct {name}")
        sb, cb = sb_layout(structs[name]), cb_layout(structs[name])
        if sb != D3D_EXPECTED["structured"][name]:
            fail(f"{name}'s StructuredBuffer layout is now {sb}, D3D_EXPECTED says "
                 f"{D3D_EXPECTED['structured'][name]}: update tests/hlsl/check_hlsl.py and docs/porting.md")
        if cb != D3D_EXPECTED["cbuffer"][name]:
            fail(f"{name}'s cbuffer layout is now {cb}, D3D_EXPECTED says {D3D_EXPECTED['cbuffer'][name]}: "
                 "update tests/hlsl/check_hlsl.py and docs/porting.md")
        h = host["host"][name]
        rows.append((name, sb, cb, (h["members"], h["size"])))

    # host.hpp against the Direct3D layouts: where they agree and where they do not, as docs/porting.md says.
    emcm2, stats, block = rows
    if emcm2[3] == emcm2[1] or emcm2[1][1] != 32 or emcm2[3][1] != 48:
        fail(f"EmcvEmcm2: host.hpp {emcm2[3]} and the StructuredBuffer layout {emcm2[1]} were 48 and 32 bytes")
    port = host["port"]["EmcvEmcm2"]
    if (port["members"], port["size"]) != emcm2[1]:
        fail(f"EmcvEmcm2: the port's C++ struct {port} no longer has the StructuredBuffer layout {emcm2[1]}")
    if emcm2[2][0] != emcm2[3][0] or (emcm2[2][1] + 15) // 16 * 16 != emcm2[3][1]:
        fail(f"EmcvEmcm2: the cbuffer layout {emcm2[2]} no longer has host.hpp's offsets, nor an array stride "
             f"of its size {emcm2[3][1]}")
    for name, sb, cb, h in (stats, block):
        if sb != h:
            fail(f"{name}: the StructuredBuffer layout {sb} is not host.hpp's {h}")
    if stats[2] != stats[3]:
        fail(f"EmcvMovingStats: the cbuffer layout {stats[2]} is not host.hpp's {stats[3]}")
    if block[2] == block[3]:
        fail("EmcvBudgetBlock: the cbuffer layout was expected to differ from host.hpp's (arrays of 16-byte rows)")

    # tools: glslang's scalar block layout (C-like, 4-byte aligned: a structured buffer's packing) of the GLSL
    # port's structs, and its std430 layout of the HLSL consumer's structured buffers (the Vulkan path of the
    # same HLSL: host.hpp), read back by spirv-cross --reflect.
    os.makedirs(args.work, exist_ok=True)
    scalar = os.path.join(args.work, "scalar_layout.comp")
    with open(scalar, "w", encoding="utf-8") as f:
        f.write("#version 450 core\n#extension GL_EXT_scalar_block_layout : require\n" + read(args.port_glsl) + """
layout(local_size_x = 1) in;
layout(scalar, binding = 0) buffer A { EmcvEmcm2 a[]; };
layout(scalar, binding = 1) buffer B { EmcvMovingStats b[]; };
layout(scalar, binding = 2) buffer C { EmcvBudgetBlock c[]; };
void main() { a[1].count = b[1].count + c[1].solves; }
""")
    run([args.glslang, "-V", scalar, "-o", scalar + ".spv"])
    reflection, types = reflect_types(args.spirv_cross, scalar + ".spv")
    for (name, sb, _, _), block_name in zip(rows, "ABC"):
        if types.get(name, [None])[0] != sb[0] or buffer_stride(reflection, block_name) != sb[1]:
            fail(f"{name}: glslang's scalar layout {types.get(name)} (stride {buffer_stride(reflection, block_name)}) "
                 f"is not the StructuredBuffer layout {sb}")
    spv = consumer_spv(args)
    reflection, types = reflect_types(args.spirv_cross, spv)
    for (name, _, _, h), block_name in zip(rows, ("covariance", "residual", "budget")):
        if types.get(name, [None])[0] != h[0] or buffer_stride(reflection, block_name) != h[1]:
            fail(f"{name}: glslang's layout of the HLSL {block_name} {types.get(name)} is not host.hpp's {h}")
    # the consumer's cbuffer: glslang lays EmcvEmcm2 and EmcvMovingStats out (std140) at the Direct3D offsets,
    # and spirv-cross, translating it back to HLSL, finds them legal under cbuffer packing.
    for name, _, cb, _ in rows[:2]:
        if any(t != cb[0] for t in types.get(name, [])):
            fail(f"{name}: glslang's cbuffer layout {types.get(name)} is not the Direct3D one {cb[0]}")
    rc, out = run([args.spirv_cross, spv, "--hlsl", "--shader-model", "51"], expect_ok=False)
    if rc != 0 or not re.search(r"EmcvEmcm2 \w*prior_state : packoffset\(c2\)", out):
        fail(f"spirv-cross does not find the consumer's cbuffer legal under HLSL packing (exit {rc}):\n{out[:2000]}")

    for name, sb, cb, h in rows:
        print(f"{name}: StructuredBuffer {sb[0]} stride {sb[1]}; cbuffer {cb[0]} size {cb[1]}; host.hpp {h[0]} size {h[1]}")
    print("hlsl layout: OK (EmcvEmcm2: StructuredBuffer 32 bytes = the port's C++ struct, not host.hpp's 48; "
          "cbuffer = host.hpp's offsets; EmcvMovingStats: host.hpp's everywhere (cbuffer arrays: stride 32); "
          "EmcvBudgetBlock: host.hpp's in a StructuredBuffer, not for a cbuffer)")


# ---- the GPU modules for HLSL (cmake/emcv_module_hlsl.cmake) -------------------------------------------------------

LANGUAGE = "emcv_adaptive_language"


def library_problems(text):
    """What keeps an HLSL file from being a library to #include: a resource, a register, an entry point, no guard."""
    code = re.sub(r"//[^\n]*", "", text)
    code = re.sub(r"#\s*error[^\n]*", "", code)  # messages may name anything
    problems = []
    for pattern, what in [(r"\bregister\s*\(", "a register"), (r"\bpackoffset\b", "a packoffset"),
                          (r"\bcbuffer\b|\btbuffer\b|\bConstantBuffer\b|\buniform\b", "a constant buffer"),
                          (r"\b(RW)?(ByteAddress|Structured)Buffer\b|\b(RW)?Texture\w*\b|\bSamplerState\b"
                           r"|\blayout\s*\(|\bbuffer\s+\w+\s*\{", "a resource"),
                          (r"\bnumthreads\b", "an entry point's [numthreads]"), (r"\bmain\s*\(", "a `main`")]:
        found = re.search(pattern, code)
        if found:
            problems.append(f"{what} ({found.group(0)!r})")
    guard = re.match(r"(?:\s*//[^\n]*\n|\s*\n)*#ifndef (\w+)\n#define \1\n", text)
    if not guard or not re.search(r"\n#endif[^\n]*\s*$", text):
        problems.append("no include guard (#ifndef X / #define X first, #endif last)")
    return problems


def hlsl_line(glsl_line, names):
    """A GLSL module's line as cmake/emcv_module_hlsl.cmake writes it into the module's HLSL file."""
    m = re.match(r'\s*#\s*include\s*(.*)$', glsl_line)
    if not m:
        return glsl_line
    target = m.group(1)
    if re.match(r'"emcv/port/[a-z_]+\.h"', target):
        return f"// {target}: emcv_port.hlsl, which the application includes first"
    m = re.fullmatch(r'"module/([a-z0-9_]+)\.glsl"', target)
    if m and m.group(1) in names:
        return f'#include "{m.group(1)}.hlsl"'
    fail(f"an #include the generator does not know: {glsl_line}")


def glsl_modules(source_dir):
    return sorted(f[:-5] for f in os.listdir(source_dir) if f.endswith(".glsl") and f != LANGUAGE + ".glsl")


def compile_hlsl(args, source, includes, defines=(), spv=None, listing=False):
    """glslang's HLSL front end on `source`: (exit code, output)."""
    command = [args.glslang, "-D", "-V", "-e", "main", "-S", "comp"] + [f"-D{d}" for d in defines]
    command += ["-I" + os.path.abspath(i) for i in includes]
    command += (["-H"] if listing else []) + [source, "-o", spv or os.path.join(args.work, "unused.spv")]
    return run(command, expect_ok=False)


def check_gpu_modules(args):
    os.makedirs(args.work, exist_ok=True)
    names = glsl_modules(args.source_modules)
    want = sorted([n + ".hlsl" for n in names] + [LANGUAGE + ".hlsl"])
    have = sorted(os.listdir(args.modules_dir))
    if have != want or not names:
        fail(f"{args.modules_dir} holds {have}, not the HLSL versions of {args.source_modules}'s modules {want}")
    if read(os.path.join(args.modules_dir, LANGUAGE + ".hlsl")) != read(
            os.path.join(args.source_modules, "hlsl", LANGUAGE + ".hlsl")):
        fail(f"{args.modules_dir}/{LANGUAGE}.hlsl is not shaders/module/hlsl's (rebuild emcv)")
    for name in want:
        problems = library_problems(read(os.path.join(args.modules_dir, name)))
        if problems:
            fail(f"{args.modules_dir}/{name} is not a library to #include: {'; '.join(problems)}")

    # one implementation: each HLSL module is its GLSL module, #include lines rewritten, after the generated header
    for name in names:
        glsl = read(os.path.join(args.source_modules, name + ".glsl")).split("\n")
        hlsl = read(os.path.join(args.modules_dir, name + ".hlsl")).split("\n")
        header = next((i + 1 for i, l in enumerate(hlsl) if l == "// The GLSL file's header follows."), len(hlsl))
        expected = [hlsl_line(l, names + [LANGUAGE]) for l in glsl[1:]]
        if not hlsl[0].startswith("// SPDX-License-Identifier") or hlsl[header:] != expected:
            line = next((i for i, (a, b) in enumerate(zip(hlsl[header:], expected)) if a != b), None)
            fail(f"{name}.hlsl is not {name}.glsl with its #includes rewritten (first difference at GLSL line "
                 f"{(line or 0) + 2}): rebuild emcv (the emcv_shader_files target)")

    # the generator, on the modules as they are now, writes these files (not stale), and refuses each construct
    fresh = os.path.join(args.work, "fresh")
    shutil.rmtree(fresh, ignore_errors=True)
    run([args.cmake, f"-DMODULE_DIR={args.source_modules}", f"-DOUTPUT_DIR={fresh}", "-P", args.generator])
    for name in want:
        if read(os.path.join(fresh, name)) != read(os.path.join(args.modules_dir, name)):
            fail(f"{args.modules_dir}/{name} is stale: the generator writes {fresh}/{name} from the modules now")
    refused = check_generator_refuses(args, names)

    # the library check refuses what a module must not hold
    sample = read(os.path.join(args.modules_dir, names[0] + ".hlsl"))
    guard_end = sample.rindex("#endif")
    def added(line):
        return sample[:guard_end] + line + "\n" + sample[guard_end:]
    for what, mutant in [("a resource", added("RWTexture2D<float4> leak : register(u7);")),
                         ("an entry point", added("[numthreads(8, 8, 1)] void main() {}")),
                         ("a constant buffer", added("cbuffer Leak { uint leak; };")),
                         ("no include guard", re.sub(r"#ifndef (\w+)\n#define \1\n", "", sample, count=1))]:
        if not library_problems(mutant):
            fail(f"the library check missed {what} added to {names[0]}.hlsl")

    # all of them after emcv_port.hlsl, twice (the guards hold), for each method: they compile, with no entry
    # point and none of the application's functions defined (they only declare them)
    for method in ("CV", "SPVG", "NOTEX"):
        wrapper = os.path.join(args.work, f"modules_{method.lower()}.hlsl")
        with open(wrapper, "w", encoding="utf-8") as f:
            f.write('#include "emcv_port.hlsl"\nRWStructuredBuffer<EmcvBudgetBlock> budget : register(u0);\n'
                    "#define EMCV_APP_BUDGET budget[0]\n#define EMCV_BUDGET_GROUP_THREADS 64\n"
                    "#define EMCV_ADAPTIVE_TILE_UPDATE 1\n#define EMCV_ADAPTIVE_PLAN_NEXT 1\n"
                    + "".join(f'#include "{n}.hlsl"\n' for n in names * 2))
        rc, out = compile_hlsl(args, wrapper, [os.path.dirname(args.module), args.modules_dir],
                               [f"EMCV_ADAPTIVE_{method}=1"])
        if "Entry point not found" not in out or "ERROR:" in out:
            fail(f"the HLSL modules for EMCV_ADAPTIVE_{method} do not compile alone, or hold an entry point "
                 f"(exit {rc}):\n{out}")
    print(f"hlsl gpu modules: OK ({len(names)} modules + {LANGUAGE}.hlsl: libraries, their GLSL code, compiled for "
          f"3 methods; the generator refuses {refused} GLSL-only constructs)")


# What the generator must refuse: (module, line added before its include guard's #endif, the rule it names).
GENERATOR_MUTANTS = [
    ("emcv_adaptive_plan", "vec4 emcv_mutant() { return vec4(0.0f); }", "HLSL has no splat"),
    ("emcv_adaptive_history", "ivec2 emcv_mutant() { return ivec2(EMCV_ADAPTIVE_TILE_SIZE); }", "HLSL has no splat"),
    ("emcv_adaptive_history",
     "EmcvAdaptiveBlock emcv_mutant() { return EmcvAdaptiveBlock(ivec2(-1, -1), ivec2(-1, -1), 0u, 0u, false); }",
     "no struct constructor"),
    ("emcv_adaptive_plan", "bool emcv_mutant(vec2 t) { return t == vec2(0.0f, 0.0f); }", "componentwise"),
    ("emcv_adaptive_plan", "bool emcv_mutant(ivec2 r) { return ivec2(1, 2) != r; }", "componentwise"),
    ("emcv_adaptive_history", "uint emcv_mutant_count = 0u;", "a global is `shared` or EMCV_STATIC"),
    ("emcv_adaptive_history", "EMCV_STATIC EmcvAdaptiveState emcv_mutant_state = emcv_adaptive_init();",
     "no global initialised by a call"),
    ("emcv_adaptive_budget", "const uint emcv_mutant_bins = 4u;", "a global constant is a #define"),
    ("emcv_adaptive_budget", "float emcv_mutant() { float t[2] = float[](1.0f, 2.0f); return t[0]; }",
     "no array constructor"),
    ("emcv_adaptive_plan", "uint emcv_mutant() { return uint(tile_code.length()); }", "no .length()"),
    ("emcv_adaptive_budget", "layout(std430, binding = 9) buffer Leak { uint leak[]; };", "no resource in a module"),
    ("emcv_adaptive_plan", "uint emcv_mutant() { return gl_GlobalInvocationID.x; }", "no GLSL built-in variable"),
    ("emcv_adaptive_layout_moving", '#include "render/frame.h"', "includes the port's headers and the modules only"),
    ("emcv_adaptive_layout_emcm2", "#extension GL_EXT_shader_atomic_float : require", "no #version, #extension"),
]


def check_generator_refuses(args, names):
    for i, (module, line, rule) in enumerate(GENERATOR_MUTANTS):
        if module not in names:
            fail(f"the mutant of {module}: no such module")
        copy = os.path.join(args.work, f"mutant_{i}")
        shutil.rmtree(copy, ignore_errors=True)
        shutil.copytree(args.source_modules, os.path.join(copy, "module"))
        path = os.path.join(copy, "module", module + ".glsl")
        text = read(path)
        end = text.rindex("#endif")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text[:end] + line + "\n" + text[end:])
        rc, out = run([args.cmake, f"-DMODULE_DIR={os.path.join(copy, 'module')}",
                       f"-DOUTPUT_DIR={os.path.join(copy, 'hlsl')}", "-P", args.generator], expect_ok=False)
        if rc == 0 or rule not in " ".join(out.split()):
            fail(f"the generator did not refuse `{line}` in {module}.glsl with '{rule}' (exit {rc}):\n{out}")
    return len(GENERATOR_MUTANTS)


# The application's own descriptors (tests/hlsl/modules/app.hlsl and its passes).
APP_DESCRIPTORS = {"app_budget", "AppFrame", "app_history_a", "app_previous_a", "app_history_b", "app_previous_b",
                   "app_plan", "app_taken", "app_material", "app_tracked"}


def narrowed_bool_vectors(listing):
    """Where glslang's SPIR-V (-H listing) takes a component of a bool vector as a bool: an HLSL vector == or !=
    where GLSL's would be one bool (glslang narrows it silently; DXC reads it otherwise)."""
    types, found = {}, []
    for line in listing.splitlines():
        m = re.match(r"\s*(\d+):\s*\d+\((\w+)\)\s+(\w+)\s*(.*)$", line)
        if not m:
            continue
        result, type_name, op, operands = m.groups()
        types[result] = type_name
        if op == "CompositeExtract" and type_name == "bool" and types.get(operands.split()[0], "").startswith("bvec"):
            found.append(line.strip())
    return found


def check_gpu_modules_consumer(args):
    os.makedirs(args.work, exist_ok=True)
    # the narrowing check finds a narrowed compare
    probe = os.path.join(args.work, "narrowing_probe.hlsl")
    with open(probe, "w", encoding="utf-8") as f:
        f.write("RWStructuredBuffer<int> o : register(u0);\n[numthreads(1, 1, 1)] void main(uint3 id : "
                "SV_DispatchThreadID) { bool same = int2(id.xy) == int2(1, 2); o[0] = same ? 1 : 0; }\n")
    rc, out = compile_hlsl(args, probe, [], listing=True)
    if rc != 0 or not narrowed_bool_vectors(out):
        fail(f"the narrowing check misses `bool same = int2(...) == int2(...)` (exit {rc}):\n{out[-2000:]}")

    # the ports: the installed one (a quality target at K = 1) and budget mode at each K
    ports = [("installed", os.path.dirname(os.path.abspath(args.module)), ["plan", "solve", "count", "update",
                                                                           "update_next", "quality"])]
    for k in (1, 2, 4):
        folder = os.path.join(args.work, f"port_budget_k{k}")
        run([args.cmake, f"-DGLSLANG={args.glslang}", f"-DSPIRV_CROSS={args.spirv_cross}",
             f"-DPORT_GLSL={args.port_glsl}", f"-DKERNEL={args.port_kernel}", f"-DWORK={folder}/work",
             f"-DOUTPUT={folder}/emcv_port_reference.hlsl", f"-DMODULE={folder}/emcv_port.hlsl",
             f"-DTUNABLES=EMCV_HISTORY_SPP_BUDGET=8.0f;EMCV_HISTORY_BLOCK={k}", "-P", args.port_script])
        ports.append((f"budget K={k}", folder, ["plan", "solve", "count", "update", "update_next"]))
    count = 0
    for port_name, port_dir, passes in ports:
        for method in ("CV", "SPVG", "NOTEX"):
            for name in passes:
                defines = [f"EMCV_ADAPTIVE_{method}=1"]
                if name == "update_next":
                    defines.append("EMCV_ADAPTIVE_PLAN_NEXT=1")
                source = os.path.join(args.consumer_dir, name.replace("_next", "") + ".comp.hlsl")
                port_tag = port_name.replace(" ", "_").replace("=", "")
                spv = os.path.join(args.work, f"{name}_{method.lower()}_{port_tag}.spv")
                what = f"{name} for EMCV_ADAPTIVE_{method} on the {port_name} port"
                rc, out = compile_hlsl(args, source, [port_dir, args.modules_dir], defines, spv, listing=True)
                if rc != 0:
                    fail(f"{what} does not compile (exit {rc}):\n{out[-4000:]}")
                narrowed = narrowed_bool_vectors(out)
                if narrowed:
                    fail(f"{what}: a bool vector read as a bool (a vector == or != in a module?): {narrowed[:3]}")
                reflection, _ = reflect_types(args.spirv_cross, spv)
                names = {r["name"] for kind in ("ssbos", "ubos", "images", "separate_images", "textures")
                         for r in reflection.get(kind, [])}
                if not names <= APP_DESCRIPTORS:
                    fail(f"{what}: descriptors {sorted(names - APP_DESCRIPTORS)} are not the application's own")
                if port_name.startswith("budget") and name in ("plan", "solve", "count") and "app_budget" not in names:
                    fail(f"{what} does not use the budget block: budget mode is not on ({sorted(names)})")
                count += 1
    print(f"hlsl gpu modules consumer: OK ({count} passes compiled: 3 methods, the installed port and budget mode "
          f"at K = 1, 2, 4; the application's descriptors only, no narrowed bool vector)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("check", choices=["module", "consumer", "layout", "gpu-modules", "gpu-modules-consumer"])
    for option in ("module", "port-glsl", "consumer", "host-layout", "glslang", "spirv-cross", "work", "modules-dir",
                   "source-modules", "generator", "cmake", "port-kernel", "port-script", "consumer-dir"):
        parser.add_argument("--" + option)
    args = parser.parse_args()
    for tool in (args.glslang, args.spirv_cross):
        if tool is not None and (not tool or not shutil.which(tool)):
            print(f"SKIP: {tool or 'glslangValidator/spirv-cross'} not found (scripts/install-deps.sh)")
            sys.exit(77)
    if not args.module or not os.path.exists(args.module):
        fail(f"no module {args.module} (built by the emcv_shader_files target)")
    {"module": check_module, "consumer": check_consumer, "layout": check_layout, "gpu-modules": check_gpu_modules,
     "gpu-modules-consumer": check_gpu_modules_consumer}[args.check](args)


if __name__ == "__main__":
    main()
