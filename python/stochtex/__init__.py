"""stochtex: procedural texture synthesis by example (docs/python.md).

    import numpy, stochtex
    model = stochtex.analyze(exemplar, "texton")        # HxWxC uint8, uint16 or float32
    image = model.render(512, 512, seed=1)              # 512x512xC float32
"""

from ._stochtex import (Model, analyze, analyze_material, compare, cpu_target, cpu_targets,
                        gaussian, load, methods, mix, read_image, set_cpu_target, write_image)

__all__ = ["Model", "analyze", "analyze_material", "compare", "cpu_target", "cpu_targets",
           "gaussian", "load", "methods", "mix", "read_image", "set_cpu_target", "write_image"]
