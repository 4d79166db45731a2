// Local random-phase noise on the GL renderer: the program (compiled with the model's constants)
// and the frequency, sub-stratum and section 5 tables as storage buffers. A material (more than 4
// channels) runs one program per chunk of up to 4 of its decorrelated channels, each adding its
// columns of the colour basis to the N output channels.

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <span>
#include <string>
#include <utility>
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
// `first_channel` and `material`: for a chunk of a material (material_chunk), the index of the
// model's first channel in the material and the GLSL of the chunk's output (empty otherwise).
class LrpPass final : public Pass {
 public:
  LrpPass(lrp::LrpModel model, int first_channel, const std::string& material)
      : model_(std::move(model)),
        first_channel_(first_channel),
        glsl_(lrp_glsl(model_)),
        program_(std::string("#version 450\n") +
                 (material.empty() ? "" : "#define LRP_MATERIAL\n") + lrp_library_source(glsl_) +
                 material + shader_source("methods/lrp/render.glsl")),
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
      seeds[s] = cell_key(lrp::channel_stream(first_channel_ + static_cast<int>(s) / d.strata),
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
  const lrp::LrpModel model_;
  const int first_channel_;
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

// Channels [first, first + count) of a material `model` as a model of its own: their strata and
// sub-strata, the whole frequency table (the sub-strata index it), their slice of the structure
// table and the same turbulence. Its mean and basis are unused (the chunk's output is
// material_output's).
lrp::LrpModel material_chunk(const lrp::LrpModel& model, int first, int count) {
  const lrp::LrpData& d = model.data();
  lrp::LrpData chunk;
  chunk.channels = count;
  chunk.strata = d.strata;
  chunk.normalise_envelope = d.normalise_envelope;
  chunk.mean.assign(static_cast<std::size_t>(count), 0.0f);
  chunk.colour_basis.assign(static_cast<std::size_t>(count) * count, 0.0f);
  for (int c = 0; c < count; ++c)
    chunk.colour_basis[static_cast<std::size_t>(c * count + c)] = 1.0f;
  const auto strata_begin = d.strata_table.begin() + first * d.strata;
  const auto strata_end = strata_begin + count * d.strata;
  chunk.strata_table.assign(strata_begin, strata_end);
  const auto cosines_of = [](int sum, const lrp::Stratum& stratum) {
    return sum + stratum.cosines;
  };
  const int substrata_begin = std::accumulate(d.strata_table.begin(), strata_begin, 0, cosines_of);
  const int substrata_end = std::accumulate(strata_begin, strata_end, substrata_begin, cosines_of);
  chunk.substratum_first.assign(d.substratum_first.begin() + substrata_begin,
                                d.substratum_first.begin() + substrata_end);
  chunk.substratum_count.assign(d.substratum_count.begin() + substrata_begin,
                                d.substratum_count.begin() + substrata_end);
  chunk.frequencies = d.frequencies;
  chunk.weights = d.weights;
  chunk.structure = d.structure;
  if (!d.structure.empty()) {
    const auto per_channel = static_cast<std::ptrdiff_t>(4) * d.structure.blocks *
                             d.structure.blocks * d.structure.cosines;
    const auto table = d.structure.cosine_table.begin() + first * per_channel;
    chunk.structure.cosine_table.assign(table, table + count * per_channel);
  }
  return lrp::LrpModel(std::move(chunk));
}

// The GLSL constants of a material chunk's output (render.glsl, LRP_MATERIAL): the material's
// channel count and mean, the chunk's first channel and its columns of the colour basis (N x
// count, row-major).
std::string material_output(const lrp::LrpModel& model, int first, int count) {
  const lrp::LrpData& d = model.data();
  std::vector<float> columns;
  for (int c = 0; c < d.channels; ++c)
    for (int k = first; k < first + count; ++k)
      columns.push_back(d.colour_basis[static_cast<std::size_t>(c * d.channels + k)]);
  return "const int LRP_MATERIAL_CHANNELS = " + glsl_int(d.channels) +
         ";\nconst int LRP_CHUNK_FIRST = " + glsl_int(first) + ";\n" +
         glsl_array("float", "LRP_MATERIAL_MEAN", std::span<const float>(d.mean), glsl_float) +
         glsl_array("float", "LRP_CHUNK_BASIS", std::span<const float>(columns), glsl_float);
}

// A material: one LrpPass per chunk of up to 4 channels, run in channel order on the same result
// buffer (each chunk adds to what the chunks before it wrote), so a sample sums mean + basis *
// noise in the CPU's order. Each chunk's strata are evaluated once; turbulence (section 5.2) is
// evaluated again by every chunk.
class LrpMaterialPass final : public Pass {
 public:
  explicit LrpMaterialPass(const lrp::LrpModel& model) {
    for (int first = 0; first < model.channels(); first += 4) {
      const int count = std::min(4, model.channels() - first);
      chunks_.push_back(std::make_unique<LrpPass>(material_chunk(model, first, count), first,
                                                  material_output(model, first, count)));
    }
  }

  void prepare(const Grid& grid, std::uint32_t seed, const GpuRenderOptions& options) override {
    for (const auto& chunk : chunks_) chunk->prepare(grid, seed, options);
  }

  void dispatch(std::int64_t first_x, std::int64_t first_y, int width, int height,
                const Buffer& result) const override {
    for (const auto& chunk : chunks_) {
      chunk->dispatch(first_x, first_y, width, height, result);
      // The next chunk reads what this one wrote.
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }

 private:
  std::vector<std::unique_ptr<LrpPass>> chunks_;
};

}  // namespace

std::unique_ptr<Pass> Twin<lrp::LrpModel>::pass(const lrp::LrpModel& model) {
  if (model.channels() > 4) return std::make_unique<LrpMaterialPass>(model);
  return std::make_unique<LrpPass>(model, 0, std::string());
}

}  // namespace stochtex::gl
