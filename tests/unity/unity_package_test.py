#!/usr/bin/python3
"""The Unity package (unity/com.stochtex.textures, docs/engines.md "Unity") without Unity.

There is no Unity here, so this checks what can be checked outside it:

- its C# (Runtime and Editor, as their .asmdef files split them) compiles with Debian's mono
  `mcs`, warnings as errors, against stubs of the Unity 2021.3 API it uses
  (tests/unity/stubs: Unity's signatures, bodies that throw);
- tests/unity/PackageTest.cs, run by mono against the stubs: a data file's texels in the order
  the exported shader reads them (rows, missing channels, 3-D slices), and the manifest.json of
  three exports read into the package's classes (every key a field, every field a key),
  each written out as its example shader;
- each example shader's program (CGPROGRAM), with the package's HLSL and the export's Shader
  Graph file, compiles in glslang's HLSL front end, vertex and fragment, in a Linear and a Gamma
  colour space project (UnityCG.cginc's UnityObjectToClipPos stood in for), and says the
  colour as the manifest does; the package's Shader Graph functions compile as a Custom Function
  node calls them.

The exports: a tiling model of grass_lawn_128 (srgb: linear light, fast variant: a 16-bit PNG
mip-mapped and a 3-D table), a texton model of it analysed as data (exact: float OpenEXR), and a
tiling material of rock_sandstone's albedo (srgb) and roughness (data).

Usage: unity_package_test.py STOCHTEX SOURCE_DIR WORK_DIR
Exit 77 (CTest's SKIP_RETURN_CODE) when mcs, mono or glslangValidator is not installed.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys


def run(*command, cwd=None, env=None):
    result = subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(map(str, command))} exited {result.returncode}:\n"
                 f"{result.stdout}{result.stderr}")
    return result.stdout


def compile_csharp(source, work):
    """The package's assemblies, as Unity would build them from its .asmdef files."""
    package = source / "unity" / "com.stochtex.textures"
    cs = work / "cs"
    cs.mkdir(parents=True, exist_ok=True)
    flags = ["-warnaserror", "-warn:4", "-nologo"]
    stubs, runtime = cs / "UnityStubs.dll", cs / "Stochtex.Textures.dll"
    editor, test = cs / "Stochtex.Textures.Editor.dll", cs / "PackageTest.exe"
    run("mcs", *flags, "-target:library", f"-out:{stubs}",
        *sorted((source / "tests" / "unity" / "stubs").glob("*.cs")))
    run("mcs", *flags, "-target:library", f"-r:{stubs}", f"-out:{runtime}",
        *sorted((package / "Runtime").glob("*.cs")))
    run("mcs", *flags, "-target:library", f"-r:{stubs}", f"-r:{runtime}", f"-out:{editor}",
        *sorted((package / "Editor").glob("*.cs")))
    run("mcs", *flags, f"-r:{stubs}", f"-r:{editor}", f"-out:{test}",
        source / "tests" / "unity" / "PackageTest.cs")
    return test


def exports(stochtex, source, work):
    """Three hlsl export folders, each with the manifest's colour of what the example shows."""
    grass = source / "data" / "exemplars" / "grass_lawn_128.png"
    rock = source / "data" / "materials" / "rock_sandstone"
    models = {
        "tiling": ["analyze", grass, "-m", "tiling"],
        "texton_data": ["analyze", grass, "-m", "texton", "-p", "support=16",
                        "--colour-space", "data"],
        "material": ["analyze", "--map", f"albedo={rock / 'albedo.png'}",
                     "--map", f"roughness={rock / 'roughness.png'}", "-m", "tiling"],
    }
    variants = {"tiling": "fast", "texton_data": "exact", "material": "exact"}
    shown = {"tiling": "linear", "texton_data": "data", "material": "linear"}
    folders = {}
    for name, analyse in models.items():
        model = work / f"{name}.stx"
        run(stochtex, *analyse, "-o", model)
        folder = work / name
        shutil.rmtree(folder, ignore_errors=True)
        run(stochtex, "export-shader", model, "-o", folder, "--language", "hlsl",
            "--variant", variants[name])
        folders[folder] = shown[name]
    return folders


def check_example(folder, colour, shaders):
    """The example shader's program through glslang's HLSL front end, both stages, both colour
    space projects."""
    text = next(folder.glob("*_example.shader")).read_text()
    linear = "#define STOCHTEX_EXAMPLE_LINEAR_LIGHT 1" in text
    if linear != (colour == "linear") or ("_StochtexDecode" in text) == linear:
        sys.exit(f"FAIL: {folder.name}'s example shader does not show {colour} as such:\n{text}")
    program = re.search(r"CGPROGRAM\n(.*?)\n\s*ENDCG", text, re.S).group(1)
    program = "\n".join(line for line in program.splitlines()
                        if not line.strip().startswith("#pragma"))
    program = program.replace('#include "UnityCG.cginc"',
                              "float4 UnityObjectToClipPos(float4 v) { return v; }")
    program = program.replace('"Packages/com.stochtex.textures/Shaders/', '"')
    for gamma in (False, True):
        hlsl = folder / f"example_{'gamma' if gamma else 'linear'}.hlsl"
        hlsl.write_text(("#define UNITY_COLORSPACE_GAMMA\n" if gamma else "") + program + "\n")
        for stage, entry in (("vert", "stochtex_example_vertex"),
                             ("frag", "stochtex_example_fragment")):
            run("glslangValidator", "-D", "-V", "--amb", "--aml", "-o", os.devnull, "-S", stage,
                "-e", entry, f"-I{shaders}", hlsl)


def check_shader_graph_functions(shaders, work):
    """The package's Custom Function bodies as Shader Graph calls them (the _float names)."""
    hlsl = work / "shader_graph_functions.hlsl"
    hlsl.write_text(
        '#include "StochtexPlacement.hlsl"\n'
        "float4 main(float4 position : SV_Position, float2 uv : TEXCOORD0) : SV_Target {\n"
        "  float2 p, dpdx, dpdy;\n"
        "  StochtexPlacement_float(uv, float2(0.0, 0.0), float2(512.0, 512.0), p, dpdx, dpdy);\n"
        "  float3 decoded, encoded;\n"
        "  StochtexSrgbDecode_float(float3(p, 0.5), decoded);\n"
        "  StochtexSrgbEncode_float(decoded, encoded);\n"
        "  return float4(encoded, dpdx.x + dpdy.y);\n}\n")
    run("glslangValidator", "-D", "-V", "--amb", "--aml", "-o", os.devnull, "-S", "frag", "-e",
        "main", f"-I{shaders}", hlsl)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    stochtex, source, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    for tool in ("mcs", "mono", "glslangValidator"):
        if shutil.which(tool) is None:
            print(f"SKIP: {tool} is not installed (scripts/install-deps.sh installs it)")
            sys.exit(77)
    test = compile_csharp(source, work)
    folders = exports(stochtex, source, work)
    env = dict(os.environ, MONO_PATH=str(test.parent))
    print(run("mono", test, *folders, env=env), end="")
    shaders = source / "unity" / "com.stochtex.textures" / "Shaders"
    for folder, colour in folders.items():
        check_example(folder, colour, shaders)
    check_shader_graph_functions(shaders, work)
    print(f"the package compiles; its layout, its manifests and {len(folders)} example shaders pass")


if __name__ == "__main__":
    main()
