#!/usr/bin/python3
"""What the OpenCL program costs a GPU, read off the compilers, with no GPU.

Compiles trac0r/kernel/render.cl (the headers the library embeds) for the
feature mask of each scene, for AMD GPUs (clang-15 with rocm-device-libs;
the code object's notes give each kernel's registers, spills, scratch and
local memory) and for NVIDIA's PTX (clang-15 with libclc; the PTX gives the
per-thread local frame, and ptxas, where CUDA is installed, the registers).
Prints Markdown tables; see README.md beside this file.
"""

import argparse
import concurrent.futures
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KERNEL_DIR = os.path.join(ROOT, "trac0r", "kernel")
SOURCE = os.path.join(KERNEL_DIR, "render.cl")
ROCM_LIBS = "/usr/lib/x86_64-linux-gnu/amdgcn/bitcode"
LIBCLC_NVPTX = "/usr/lib/clc/nvptx64--nvidiacl.bc"
TILE_ITEMS = 64  # render_frame's work-group with the BVH: one 8 x 8 tile

# Per AMD target: wave size, VGPRs a SIMD holds per lane, the most waves a
# SIMD runs, SIMDs per compute unit (64 KB of LDS each CU). RDNA2 (gfx1030)
# runs wave32; CDNA2 and CDNA3 (gfx90a, gfx940) wave64, with the AGPRs in
# the same 512 registers (their VGPR column counts both).
AMD_TARGETS = {
    "gfx1030": {"wave": 32, "vgprs": 1024, "waves": 16, "simds": 2},
    "gfx90a": {"wave": 64, "vgprs": 512, "waves": 8, "simds": 4},
    "gfx940": {"wave": 64, "vgprs": 512, "waves": 8, "simds": 4},
}
LDS_PER_CU = 65536
NVIDIA_ARCHS = ["sm_80", "sm_90"]  # with ptxas only


def run(command):
    p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("gpu_resources: %s failed:\n%s" % (" ".join(command), p.stderr.strip()))
    return p.stdout + p.stderr


def need(tool, package):
    if shutil.which(tool) is None:
        sys.exit("gpu_resources: needs %s (apt-get install %s)" % (tool, package))


def scene_masks(viewer, scenes):
    """(label, mask) per scene: the mask the viewer reports at one sample,
    and the thesis' flat list for the first scene."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, scene in enumerate(scenes):
            accels = ["bvh", "flat"] if i == 0 else ["bvh"]
            for accel in accels:
                text = run([viewer, scene, "--headless", "--backend", "cpu", "--accel", accel,
                            "--width", "8", "--height", "8", "--spp", "1", "--verbose",
                            "--output", os.path.join(tmp, "out.pfm")])
                m = re.search(r"mask (0x[0-9a-f]+)", text)
                if m is None:
                    sys.exit("gpu_resources: %s printed no feature mask" % scene)
                label = os.path.basename(scene) + ("" if accel == "bvh" else " (flat)")
                out.append((label, int(m.group(1), 16)))
    return out


def cl_flags(mask):
    # clang leaves __OPENCL_VERSION__ to the OpenCL runtime (PoCL defines
    # it): defined here as an OpenCL 1.2 device would.
    return ["-x", "cl", "-cl-std=CL1.2", "-D__OPENCL_VERSION__=120", "-Xclang",
            "-finclude-default-header", "-O3",
            "-DT0_FEATURES=0x%xu" % mask, "-DT0_GPU=1", "-I", KERNEL_DIR, "-Werror"]


def amd_kernels(mask, target, tmp):
    obj = os.path.join(tmp, "%x_%s.o" % (mask, target))
    run(["clang-15", "-target", "amdgcn-amd-amdhsa", "-mcpu=" + target,
         "--rocm-device-lib-path=" + ROCM_LIBS] + cl_flags(mask) + [SOURCE, "-o", obj])
    notes = run(["llvm-readelf", "--notes", obj])
    kernels = {}
    # amdhsa.kernels: one item a kernel ("  - "), its keys four spaces in
    # (its arguments' keys are deeper).
    for block in re.split(r"\n  - (?=\.)", notes)[1:]:
        block = "\n    " + block
        name = re.search(r"\n    \.name:\s+(\S+)", block)
        if name is None or "\n    .vgpr_count:" not in block:
            continue

        def field(key):
            m = re.search(r"\n    \.%s:\s+(\d+)" % key, block)
            return int(m.group(1)) if m else 0

        kernels[name.group(1)] = {
            "vgpr": field("vgpr_count"),
            "agpr": field("agpr_count"),
            "sgpr": field("sgpr_count"),
            "vspill": field("vgpr_spill_count"),
            "scratch": field("private_segment_fixed_size"),
            "lds": field("group_segment_fixed_size"),
        }
    return kernels


def waves_per_simd(k, target):
    t = AMD_TARGETS[target]
    # On gfx90a and gfx940 .vgpr_count already holds the AGPRs (the
    # unified file); gfx1030 has none.
    registers = 8 * math.ceil(k["vgpr"] / 8.0)
    waves = min(t["waves"], t["vgprs"] // max(registers, 1))
    if k["lds"] > 0:
        groups = LDS_PER_CU // k["lds"]
        # Only render_frame's BVH path has local memory: a tile a work-group.
        group_waves = math.ceil(TILE_ITEMS / float(t["wave"]))
        waves = min(waves, groups * group_waves // t["simds"])
    return waves


def nvptx_kernels(mask, tmp):
    ptx = os.path.join(tmp, "%x.ptx" % mask)
    run(["clang-15", "-target", "nvptx64-unknown-nvidiacl", "-Xclang", "-mlink-builtin-bitcode",
         "-Xclang", LIBCLC_NVPTX, "-S"] + cl_flags(mask) + [SOURCE, "-o", ptx])
    text = open(ptx).read()
    kernels = {}
    # Each .entry's body up to the next function: its __local_depot is its
    # local frame. Functions it calls would add theirs: such PTX is refused.
    parts = re.split(r"\n(?=\.(?:visible )?\.?(?:entry|func) )", text)
    functions = 0
    for part in parts:
        m = re.match(r"\.(?:visible )?\.?(entry|func)\s+(?:\([^)]*\)\s*)?(\w+)", part)
        if m is None:
            continue
        functions += 1
        depot = re.search(r"__local_depot\d+\[(\d+)\]", part)
        if m.group(1) == "entry":
            kernels[m.group(2)] = {"local": int(depot.group(1)) if depot else 0}
    if functions != len(kernels):
        sys.exit("gpu_resources: the PTX of mask 0x%x has functions besides its kernels; "
                 "their frames would not be counted" % mask)
    if shutil.which("ptxas"):
        for arch in NVIDIA_ARCHS:
            info = run(["ptxas", "-arch=" + arch, "-v", ptx, "-o", os.devnull])
            for name, body in re.findall(r"Compiling entry function '(\w+)'.*?\n(.*?)(?=\nptxas info\s+: Compil|\Z)",
                                         info, re.S):
                regs = re.search(r"Used (\d+) registers", body)
                stack = re.search(r"(\d+) bytes stack frame, (\d+) bytes spill stores", body)
                kernels[name][arch] = (int(regs.group(1)), int(stack.group(1)), int(stack.group(2)))
    return kernels


def compile_mask(mask, targets, tmp):
    out = {}
    for target in targets:
        out[target] = nvptx_kernels(mask, tmp) if target == "nvptx" else amd_kernels(mask, target, tmp)
    return mask, out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="*", help="scene files (default: scenes/*.json)")
    parser.add_argument("--viewer", default=os.path.join(ROOT, "build", "trac0r_viewer"),
                        help="trac0r_viewer, to read each scene's feature mask")
    parser.add_argument("--masks", help="comma-separated feature masks instead of scenes")
    parser.add_argument("--targets", default="gfx1030,gfx90a,gfx940,nvptx",
                        help="AMD processors and/or nvptx (default: %(default)s)")
    parser.add_argument("--kernel", default="render_frame", help="kernel of the per-mask table")
    parser.add_argument("--tsv", action="store_true",
                        help="print one line per mask, scene, AMD target and kernel instead: "
                             "mask scene target kernel VGPRs SGPRs spills scratch LDS")
    args = parser.parse_args()
    need("clang-15", "clang-15")
    need("llvm-readelf", "llvm")
    targets = args.targets.split(",")
    for t in targets:
        if t != "nvptx" and t not in AMD_TARGETS:
            sys.exit("gpu_resources: --targets: unknown target '%s' (known: %s, nvptx)" %
                     (t, ", ".join(AMD_TARGETS)))
    if any(t in AMD_TARGETS for t in targets) and not os.path.isdir(ROCM_LIBS):
        sys.exit("gpu_resources: needs AMD's device libraries in %s (apt-get install "
                 "rocm-device-libs)" % ROCM_LIBS)
    if "nvptx" in targets and not os.path.isfile(LIBCLC_NVPTX):
        sys.exit("gpu_resources: needs %s (apt-get install libclc-15)" % LIBCLC_NVPTX)

    if args.masks:
        labels = [(m, int(m, 16)) for m in args.masks.split(",")]
    else:
        scenes = args.scenes or sorted(glob.glob(os.path.join(ROOT, "scenes", "*.json")))
        if not os.access(args.viewer, os.X_OK):
            sys.exit("gpu_resources: --viewer %s is not a program (build trac0r_viewer, or "
                     "give --masks)" % args.viewer)
        cornell = [s for s in scenes if os.path.basename(s) == "cornell.json"]
        scenes = cornell + [s for s in scenes if s not in cornell]
        labels = scene_masks(args.viewer, scenes)
    masks = sorted(set(m for _, m in labels))
    print("Compiling %d feature masks for %s ..." % (len(masks), ", ".join(targets)),
          file=sys.stderr)
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for mask, out in pool.map(lambda m: compile_mask(m, targets, tmp), masks):
                results[mask] = out

    scenes_of = {}
    for label, mask in labels:
        scenes_of.setdefault(mask, []).append(label)
    if args.tsv:
        for label, mask in labels:
            for target in targets:
                for name, k in sorted(results[mask][target].items()):
                    if target != "nvptx":
                        print("0x%x\t%s\t%s\t%s\t%d\t%d\t%d\t%d\t%d" %
                              (mask, label, target, name, k["vgpr"], k["sgpr"], k["vspill"],
                               k["scratch"], k["lds"]))
        return
    kernel = args.kernel
    for target in targets:
        print()
        if target == "nvptx":
            archs = [a for a in NVIDIA_ARCHS if a in results[masks[0]]["nvptx"][kernel]]
            head = "| mask | scenes | PTX local frame B |" + "".join(
                " %s registers | %s stack B | %s spill B |" % (a, a, a) for a in archs)
            print("%s, NVPTX (clang-15, libclc%s):\n" % (kernel, ", ptxas" if archs else ""))
            print(head)
            print("|" + " --- |" * (head.count("|") - 1))
            for mask in masks:
                k = results[mask]["nvptx"][kernel]
                print("| 0x%x | %s | %d |" % (mask, ", ".join(scenes_of[mask]), k["local"]) +
                      "".join(" %d | %d | %d |" % k[a] for a in archs))
            continue
        print("%s, AMD %s (clang-15, wave%d):\n" % (kernel, target, AMD_TARGETS[target]["wave"]))
        print("| mask | scenes | VGPRs | AGPRs | SGPRs | VGPR spills | scratch B | LDS B | waves/SIMD |")
        print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for mask in masks:
            k = results[mask][target][kernel]
            print("| 0x%x | %s | %d | %d | %d | %d | %d | %d | %d |" %
                  (mask, ", ".join(scenes_of[mask]), k["vgpr"], k["agpr"], k["sgpr"], k["vspill"],
                   k["scratch"], k["lds"], waves_per_simd(k, target)))
    # The other kernels do not depend on the mask: once, from the first.
    print("\nThe other kernels (the same for every mask):\n")
    print("| kernel | target | VGPRs | SGPRs | spills | scratch B | LDS B / PTX local B |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
    for target in targets:
        for name, k in sorted(results[masks[0]][target].items()):
            if name == kernel:
                continue
            if target == "nvptx":
                print("| %s | nvptx | | | | | %d |" % (name, k["local"]))
            else:
                print("| %s | %s | %d | %d | %d | %d | %d |" %
                      (name, target, k["vgpr"], k["sgpr"], k["vspill"], k["scratch"], k["lds"]))


if __name__ == "__main__":
    main()
