// Local random-phase noise on the GL renderer: the program (compiled with the model's constants)
// and the frequency, sub-stratum and section 5 tables as storage buffers.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/hash.hpp"
#include "gl/shaders.hpp"
#include "gl/twin.hpp"
#include "methods/lrp/evaluate.hpp"
#include "methods/lrp/gl_twin.hpp"
#include "methods/lrp/structure.hpp"

namespace stochtex::gl {
namespace {

// Entry i of the origin_node/turbulence_node and *_offset uniforms: the lattice node nearest
// (u, v) (low 32 bits, as cell_key takes it) and the offset from it, as the CPU's nearest_node.
void put_nearest_node(double u, double v, std::size_t i, std::vector<GLuint>& nodes,
                      std::vector<float>& offsets) {
  const lrp::NearestNode node = lrp::nearest_node(u, v);
  nodes[2 * i] = static_cast<GLuint>(node.x);
  nodes[2 * i + 1] = static_cast<GLuint>(node.y);
  offsets[2 * i] = node.offset_x;
  offsets[2 * i + 1] = node.offset_y;
}

// The LRP evaluator's GPU state: the program (compiled with the model's constants) and the
// frequency and sub-stratum tables, in the smallest exact format: tightly packed std430 arrays of
// the C++ floats and uint32 counts (no padding channel, no integer stored as a float). The GLSL
// has no doubles: positions come split into a lattice node and a float offset (prepare).
class LrpPass final : public Pass {
 public:
  explicit LrpPass(const lrp::LrpModel& model)
      : model_(model),
        glsl_(lrp_glsl(model)),
        program_(std::string("#version 450\n") + lrp_library_source(glsl_) +
                 shader_source("methods/lrp/render.glsl")),
        frequencies_(glsl_.frequencies.size() * sizeof(float), glsl_.frequencies.data()),
        substrata_(glsl_.substrata.size() * sizeof(std::uint32_t), glsl_.substrata.data()),
        structure_(glsl_.structure.size() * sizeof(float), glsl_.structure.data()),
        turbulence_frequencies_(glsl_.turbulence_frequencies.size() * sizeof(float),
                                glsl_.turbulence_frequencies.data()),
        turbulence_substrata_(glsl_.turbulence_substrata.size() * sizeof(std::uint32_t),
                              glsl_.turbulence_substrata.data()) {
    check_gl("uploading the lrp model");
  }

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    const bool filter = options.filter;
    // Per stratum, as the CPU evaluator: the nearest lattice node of the origin (in double) and
    // the stratum's stream cell_key(channel, stratum, seed, phases).
    const lrp::LrpData& d = model_.data();
    const std::size_t strata = d.strata_table.size();
    std::vector<GLuint> nodes(2 * strata);
    std::vector<float> offsets(2 * strata);
    std::vector<GLuint> seeds(strata);
    for (std::size_t s = 0; s < strata; ++s) {
      const double inverse_spacing = 1.0 / static_cast<double>(d.strata_table[s].spacing);
      const double u = grid.origin.x * inverse_spacing;
      const double v = grid.origin.y * inverse_spacing;
      put_nearest_node(u, v, s, nodes, offsets);
      seeds[s] = cell_key(static_cast<std::int64_t>(s) / d.strata,
                          static_cast<std::int64_t>(s) % d.strata, seed, Stream::phases);
    }
    const auto count = static_cast<GLsizei>(strata);
    glProgramUniform2uiv(program_.id(), program_.location("origin_node"), count, nodes.data());
    glProgramUniform2fv(program_.id(), program_.location("origin_offset"), count, offsets.data());
    glProgramUniform1uiv(program_.id(), program_.location("stratum_seed"), count, seeds.data());
    program_.set("scale", static_cast<float>(grid.scale));
    program_.set("filtered", filter ? 1 : 0);
    if (!d.structure.empty()) prepare_structure(grid, seed);
    check_gl("setting the lrp uniforms");
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, frequencies_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, substrata_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, structure_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, turbulence_frequencies_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, turbulence_substrata_.id());
    run_tile(program_, first_x, first_y, width, height, result);
  }

 private:
  const lrp::LrpModel& model_;
  LrpGlsl glsl_;
  Program program_;
  Buffer frequencies_;
  Buffer substrata_;
  Buffer structure_;
  Buffer turbulence_frequencies_;
  Buffer turbulence_substrata_;

  // Section 5: the grid origin's far part, formed in double as add_structure does (the structure
  // is T-periodic, placement blocks and turbulence nodes are 64-bit indices).
  void prepare_structure(const Grid& grid, std::uint32_t seed) const {
    const lrp::StructureData& st = model_.data().structure;
    const double period = st.period;
    program_.set2("structure_origin",
                  static_cast<float>(grid.origin.x - period * std::floor(grid.origin.x / period)),
                  static_cast<float>(grid.origin.y - period * std::floor(grid.origin.y / period)));
    const double gx = grid.origin.x / (0.5 * period) - 0.5;
    const double gy = grid.origin.y / (0.5 * period) - 0.5;
    const double base_x = std::floor(gx);
    const double base_y = std::floor(gy);
    program_.set2("placement_block", low_bits(base_x), low_bits(base_y));
    program_.set2("placement_offset", static_cast<float>(gx - base_x),
                  static_cast<float>(gy - base_y));
    program_.set("seed", static_cast<unsigned>(seed));
    const std::size_t strata = st.turbulence_strata.size();
    if (strata == 0) return;
    std::vector<GLuint> nodes(2 * strata);
    std::vector<float> offsets(2 * strata);
    std::vector<GLuint> seeds(2 * strata);
    for (std::size_t t = 0; t < strata; ++t) {
      const double u = grid.origin.x / static_cast<double>(st.turbulence_strata[t].spacing);
      const double v = grid.origin.y / static_cast<double>(st.turbulence_strata[t].spacing);
      put_nearest_node(u, v, t, nodes, offsets);
      for (std::size_t axis = 0; axis < 2; ++axis)
        seeds[axis * strata + t] =
            cell_key(lrp::kTurbulenceStreamBase + static_cast<std::int64_t>(axis),
                     static_cast<std::int64_t>(t), seed, Stream::phases);
    }
    const auto count = static_cast<GLsizei>(strata);
    glProgramUniform2uiv(program_.id(), program_.location("turbulence_node"), count, nodes.data());
    glProgramUniform2fv(program_.id(), program_.location("turbulence_offset"), count,
                        offsets.data());
    glProgramUniform1uiv(program_.id(), program_.location("turbulence_seed"), 2 * count,
                         seeds.data());
  }
};

}  // namespace

std::unique_ptr<Pass> Twin<lrp::LrpModel>::pass(const lrp::LrpModel& model) {
  return std::make_unique<LrpPass>(model);
}

}  // namespace stochtex::gl
