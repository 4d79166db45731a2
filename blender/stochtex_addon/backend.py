"""What the add-on asks of stochtex: an analysis, a bake, the tiling fast variant's export.

The analysis and the bake go through the Python module (`import stochtex`: Debian's Blender runs
the system Python, where scripts/install-python.sh installs it) when it imports, else through the
`stochtex` command line; the export needs the command line (the module renders on the CPU only
and links no shader exporter, docs/python.md).
"""

import os
import shutil
import subprocess


class StochtexError(Exception):
    """A failure the operator reports to the user as it is (one sentence)."""


def python_module():
    """The stochtex module, or None where it is not installed."""
    try:
        import stochtex
    except ImportError:
        return None
    return stochtex


def command_line(configured=""):
    """The stochtex executable: the add-on preference's path, else `stochtex` on PATH."""
    if configured:
        path = os.path.abspath(os.path.expanduser(configured))
        if not os.access(path, os.X_OK):
            raise StochtexError("the stochtex command set in the add-on's preferences (%s) is "
                                "not an executable file" % path)
        return path
    return shutil.which("stochtex")


def _run(arguments):
    completed = subprocess.run(arguments, capture_output=True, text=True)
    if completed.returncode != 0:
        lines = [line for line in completed.stderr.splitlines() if line.strip()]
        raise StochtexError(lines[-1] if lines else "%s failed (exit code %d)" %
                            (" ".join(arguments[:2]), completed.returncode))
    return completed


def parse_parameters(text):
    """The operator's Parameters, "name=value name=value", as {name: value} (the texts)."""
    parameters = {}
    for pair in text.split():
        name, equals, value = pair.partition("=")
        if not (name and equals and value):
            raise StochtexError("the parameters are name=value pairs separated by spaces, and "
                                "'%s' is not one" % pair)
        parameters[name] = value
    return parameters


def _number_or_text(value):
    """A parameter's value as the module takes it: a number, or a choice's name."""
    for kind in (int, float):
        try:
            return kind(value)
        except ValueError:
            pass
    return value


class Backend:
    """The module or the command line, chosen once: `use` is "auto" (the module where it
    imports), "module" or "command_line"."""

    def __init__(self, use="auto", command_path=""):
        self.module = python_module() if use in ("auto", "module") else None
        if use == "module" and self.module is None:
            raise StochtexError("the stochtex Python module does not import in Blender's Python "
                                "(bash scripts/install-python.sh installs it)")
        self.command = command_line(command_path)
        if self.module is None and self.command is None:
            raise StochtexError("neither the stochtex Python module nor the stochtex command was "
                                "found: install either, or set the command's path in the add-on's "
                                "preferences")

    def analyse(self, source, method, parameters, model_path):
        """Analyses `source` (an ExemplarSource) with `method` and its `parameters` ({name:
        value}, parse_parameters) as its colour space says, writes the model to `model_path` and
        returns (what analysed it: "Python module" or "command
        line", the colour space analysed: "srgb", "linear" or "data"). An image longer than the
        method analyses (`analysis_side`: 1024 pixels, 512 for gabor) goes to the command line
        where there is one, which downscales it in linear light (docs/inputs.md); the module
        analyses the pixels it is given, at their size."""
        use_module = self.module is not None
        if use_module and self.command:
            side = next(m["analysis_side"] for m in self.module.methods() if m["name"] == method)
            use_module = max(source.image.size) <= side
        colour = source.colour(from_pixels=use_module)
        if use_module:
            try:
                model = self.module.analyze(source.array(), method, colour=colour,
                                            **{name: _number_or_text(value)
                                               for name, value in parameters.items()})
                model.save(model_path)
            except (ValueError, OSError, RuntimeError) as error:
                raise StochtexError(str(error)) from error
            return "Python module", colour
        _run([self.command, "analyze", source.file(), "--method", method, "--colour-space",
              colour, "-o", model_path] +
             [argument for name, value in parameters.items()
              for argument in ("-p", "%s=%s" % (name, value))])
        return "command line", colour

    def bake(self, model_path, image_path, width, height, seed, periodic):
        """Renders the model into `image_path` (PNG: sRGB-encoded colour for a model of colour,
        OpenEXR: linear light; a model of data: its values in both)."""
        if self.module:
            try:
                model = self.module.load(model_path)
                image = model.render(width, height, seed=seed, periodic=periodic)
                colour = "data" if model.colour_space == "data" else "linear"
                self.module.write_image(image_path, image, colour=colour)
            except (ValueError, OSError, RuntimeError) as error:
                raise StochtexError(str(error)) from error
        else:
            _run([self.command, "render", model_path, "-o", image_path, "--size",
                  "%dx%d" % (width, height), "--seed", str(seed)] +
                 (["--periodic"] if periodic else []))

    def export_fast(self, model_path, folder):
        """`stochtex export-shader --variant fast --language glsl` into `folder`."""
        if self.command is None:
            raise StochtexError("the tiling node group needs the stochtex command "
                                "(export-shader), which was not found: install it or set its "
                                "path in the add-on's preferences")
        _run([self.command, "export-shader", model_path, "-o", folder, "--variant", "fast",
              "--language", "glsl"])
