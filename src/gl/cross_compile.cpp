// GLSL 4.50 -> SPIR-V (glslang) -> GLSL ES 3.00 / HLSL / Metal (SPIRV-Cross's C API), and
// -> Godot 3 (godot_shader.hpp).
//
// SPIR-V needs an entry point, so the library is compiled inside a fragment shader whose main()
// calls the exported function once with zeros. Neither glslang (no optimiser run) nor SPIRV-Cross
// inlines functions, and both keep OpName names, so the library comes out function for function
// with its names and parameters; the entry point SPIRV-Cross writes last is then cut off. The
// values glslang leaves unnamed (calls' results, arguments' copies, temporaries, constant arrays)
// are named by spirv_names.hpp, so that the source reads as the GLSL does.
//
// Godot 3's language has no structs, global variables or arrays as arguments, which the libraries
// use, so for it main() reads the arguments from inputs and stores the result in an output, and
// spirv-opt's legalization passes (SPIRV-Tools, linked; the passes that make HLSL's SPIR-V legal
// for Vulkan) inline every function into main() and split the structs into their members;
// godot_from_essl writes what is left in Godot's subset. They keep every float operation as it
// is (measured: the Godot text run as GLSL ES matches the CPU as the GLSL ES export does). With
// the performance passes (spirv-opt -O), which also reorder arithmetic, lrp's text was 0.3 away
// from the CPU (not traced further). Its values are not renamed: the inlined function's values
// are not those spirv_names.hpp names (calls, arguments), which inlining removes.

#include "gl/cross_compile.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv_cross_c.h>

#include <array>
#include <memory>
#include <mutex>
#include <spirv-tools/optimizer.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/godot_shader.hpp"
#include "gl/shaders.hpp"
#include "gl/spirv_names.hpp"

namespace stochtex::gl {
namespace {

void initialise_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// Parses and links `source` as a fragment shader; fills `spirv` (when given) from GLSL 4.50.
// Returns glslang's log on failure, empty on success.
std::string compile(std::string_view source, ShaderLanguage language,
                    std::vector<unsigned>* spirv) {
  initialise_glslang();
  glslang::TShader shader(EShLangFragment);
  const std::string text(source);
  const char* strings = text.c_str();
  shader.setStrings(&strings, 1);
  auto messages = static_cast<EShMessages>(EShMsgDefault);
  if (language == ShaderLanguage::hlsl) {
    shader.setEnvInput(glslang::EShSourceHlsl, EShLangFragment, glslang::EShClientOpenGL, 450);
    shader.setEntryPoint("main");
    messages = static_cast<EShMessages>(messages | EShMsgReadHlsl);
  } else if (spirv != nullptr) {
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangFragment, glslang::EShClientOpenGL, 450);
    shader.setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
    messages = static_cast<EShMessages>(messages | EShMsgSpvRules);
  }
  const int version = language == ShaderLanguage::essl ? 300 : 450;
  const EProfile profile = language == ShaderLanguage::essl ? EEsProfile : ECoreProfile;
  if (!shader.parse(GetDefaultResources(), version, profile, false, false, messages))
    return std::string(shader.getInfoLog()) + shader.getInfoDebugLog();
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) return std::string(program.getInfoLog()) + program.getInfoDebugLog();
  if (spirv != nullptr) {
    glslang::SpvOptions options;
    options.disableOptimizer = true;
    glslang::GlslangToSpv(*program.getIntermediate(EShLangFragment), *spirv, &options);
  }
  return {};
}

// What a target lacks that SPIR-V can declare: the capability, and the sentence's reason.
struct Lack {
  ShaderLanguage language;
  SpvCapability capability;
  const char* reason;
};
constexpr std::array<Lack, 6> kLacks = {{
    {ShaderLanguage::essl, SpvCapabilityFloat64,
     "computes in double precision, which GLSL ES 3.00 does not have"},
    {ShaderLanguage::essl, SpvCapabilityInt64,
     "uses 64-bit integers, which GLSL ES 3.00 does not have"},
    {ShaderLanguage::hlsl, SpvCapabilityFloat64,
     "computes in double precision, which HLSL Shader Model 5 cannot express (no double sqrt, "
     "double division only as an optional feature)"},
    {ShaderLanguage::msl, SpvCapabilityFloat64,
     "computes in double precision, which Metal does not have"},
    {ShaderLanguage::godot, SpvCapabilityFloat64,
     "computes in double precision, which Godot's shading language does not have"},
    {ShaderLanguage::godot, SpvCapabilityInt64,
     "uses 64-bit integers, which Godot's shading language does not have"},
}};

// SPIRV-Cross's backend for a cross-compiled language (a switch, so that the compiler asks for a
// new language's).
spvc_backend backend(ShaderLanguage language) {
  switch (language) {
    case ShaderLanguage::essl:
    case ShaderLanguage::godot:
      return SPVC_BACKEND_GLSL;
    case ShaderLanguage::hlsl:
      return SPVC_BACKEND_HLSL;
    case ShaderLanguage::msl:
      return SPVC_BACKEND_MSL;
    case ShaderLanguage::glsl:
      break;
  }
  throw std::logic_error("cross_compile: GLSL is not cross-compiled");
}

// SPIRV-Cross through its C API: one context per call, freed on every path.
class Cross {
 public:
  Cross() {
    if (spvc_context_create(&context_) != SPVC_SUCCESS)
      throw std::logic_error("cross_compile: SPIRV-Cross could not create a context");
    spvc_context_set_error_callback(
        context_,
        [](void* log, const char* message) { *static_cast<std::string*>(log) += message; }, &log_);
  }
  ~Cross() { spvc_context_destroy(context_); }
  Cross(const Cross&) = delete;
  Cross& operator=(const Cross&) = delete;

  void check(spvc_result result, const char* step) const {
    if (result != SPVC_SUCCESS)
      throw std::logic_error(std::string("cross_compile: SPIRV-Cross failed to ") + step + ": " +
                             log_);
  }
  spvc_context context() const { return context_; }

 private:
  spvc_context context_ = nullptr;
  std::string log_;
};

// The fragment shader whose SPIR-V is cross-compiled: the library after what the targets lack
// (portable.glsl; for Godot also its float images' decoding, godot_texel.glsl), and a main()
// calling `function`, with zeros or (Godot) with its inputs, storing the result.
std::string wrapper(std::string_view library, std::string_view function, ShaderLanguage language) {
  const std::string head = "#version 450\n" + shader_source("gl/portable.glsl");
  if (language != ShaderLanguage::godot)
    return head + std::string(library) + "void main() {\n  " + std::string(function) +
           "(vec2(0.0), vec2(0.0), vec2(0.0), 0u);\n}\n";
  return head + shader_source("gl/godot_texel.glsl") + std::string(library) +
         "layout(location = 0) in vec2 p;\nlayout(location = 1) in vec2 dpdx;\n"
         "layout(location = 2) in vec2 dpdy;\nlayout(location = 3) flat in uint seed;\n"
         "layout(location = 0) out vec4 stochtex_result;\nvoid main() {\n  stochtex_result = " +
         std::string(function) + "(p, dpdx, dpdy, seed);\n}\n";
}

// spirv-opt's legalization passes (inlining, the structs' and arrays' scalar replacement, dead code
// removal, exact constant folding) on `spirv`.
std::vector<unsigned> inlined(const std::vector<unsigned>& spirv) {
  spvtools::Optimizer optimizer(SPV_ENV_UNIVERSAL_1_0);
  std::string log;
  optimizer.SetMessageConsumer(
      [&log](spv_message_level_t level, const char*, const spv_position_t&, const char* message) {
        if (level <= SPV_MSG_ERROR) log += message;
      });
  optimizer.RegisterLegalizationPasses();
  std::vector<unsigned> result;
  if (!optimizer.Run(spirv.data(), spirv.size(), &result))
    throw std::logic_error("cross_compile: spirv-opt failed: " + log);
  return result;
}

}  // namespace

std::string front_end_errors(std::string_view source, ShaderLanguage language) {
  if (language == ShaderLanguage::msl || language == ShaderLanguage::godot)
    throw std::invalid_argument("front_end_errors: glslang has no Metal or Godot front end");
  return compile(source, language, nullptr);
}

std::string cross_compile(std::string_view library, std::string_view function,
                          std::string_view method, ShaderLanguage language) {
  if (language == ShaderLanguage::glsl)
    throw std::logic_error("cross_compile: GLSL is not cross-compiled");
  const std::string_view entry = language_row(language).entry_point_start;
  const bool godot = language == ShaderLanguage::godot;
  std::vector<unsigned> spirv;
  const std::string glsl = wrapper(library, function, language);
  const std::string errors = compile(glsl, ShaderLanguage::glsl, &spirv);
  if (!errors.empty())
    throw std::logic_error("cross_compile: glslang refused the " + std::string(method) +
                           " library: " + errors);
  if (godot) spirv = inlined(spirv);

  Cross cross;
  spvc_parsed_ir ir = nullptr;
  cross.check(spvc_context_parse_spirv(cross.context(), spirv.data(), spirv.size(), &ir),
              "parse the SPIR-V");
  spvc_compiler compiler = nullptr;
  cross.check(spvc_context_create_compiler(cross.context(), backend(language), ir,
                                           SPVC_CAPTURE_MODE_TAKE_OWNERSHIP, &compiler),
              "create a compiler");
  if (!godot)
    for (const SpirvName& name : readable_names(spirv, glsl))
      spvc_compiler_set_name(compiler, name.id, name.name.c_str());

  const SpvCapability* capabilities = nullptr;
  std::size_t count = 0;
  cross.check(spvc_compiler_get_declared_capabilities(compiler, &capabilities, &count),
              "list the capabilities");
  for (const Lack& lack : kLacks)
    for (std::size_t i = 0; i < count; ++i)
      if (lack.language == language && capabilities[i] == lack.capability)
        throw std::invalid_argument(
            "the " + std::string(method) + " shader cannot be exported as " +
            std::string(language_row(language).title) + ": it " + lack.reason +
            "; export its float-only shader with --variant fast, or use "
            "--language glsl (OpenGL 4.0 or later)");

  spvc_compiler_options options = nullptr;
  cross.check(spvc_compiler_create_compiler_options(compiler, &options), "make options");
  switch (language) {
    case ShaderLanguage::essl:
    case ShaderLanguage::godot:
      cross.check(spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_GLSL_VERSION, 300),
                  "set the version");
      cross.check(spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_GLSL_ES, SPVC_TRUE),
                  "select ES");
      cross.check(
          spvc_compiler_options_set_bool(
              options, SPVC_COMPILER_OPTION_GLSL_ES_DEFAULT_FLOAT_PRECISION_HIGHP, SPVC_TRUE),
          "set highp");
      break;
    case ShaderLanguage::hlsl: {
      cross.check(
          spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_HLSL_SHADER_MODEL, 50),
          "set the shader model");
      // GLSL's samplers all default to binding 0; without a binding the textures get no
      // register(), so that the engine's compiler places them among its own.
      spvc_resources resources = nullptr;
      const spvc_reflected_resource* textures = nullptr;
      std::size_t texture_count = 0;
      cross.check(spvc_compiler_create_shader_resources(compiler, &resources),
                  "list the resources");
      cross.check(spvc_resources_get_resource_list_for_type(
                      resources, SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, &textures, &texture_count),
                  "list the textures");
      for (std::size_t i = 0; i < texture_count; ++i)
        spvc_compiler_unset_decoration(compiler, textures[i].id, SpvDecorationBinding);
      break;
    }
    case ShaderLanguage::msl:
      cross.check(spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_MSL_VERSION,
                                                 SPVC_MAKE_MSL_VERSION(1, 2, 0)),
                  "set the Metal version");
      break;
    case ShaderLanguage::glsl:
      break;
  }
  cross.check(spvc_compiler_install_compiler_options(compiler, options), "install the options");
  const char* text = nullptr;
  cross.check(spvc_compiler_compile(compiler, &text), "write the source");

  std::string source(text);
  if (godot) {
    const GodotLibrary godot_library = godot_from_essl(source, function);
    std::string result;
    for (const std::string& uniform : godot_library.uniforms) result += uniform + "\n";
    return result + "\n" + godot_library.functions;
  }
  const std::size_t cut = source.rfind(entry);
  if (cut == std::string::npos)
    throw std::logic_error("cross_compile: no entry point in SPIRV-Cross's output");
  source.erase(cut + 1);
  if (language == ShaderLanguage::essl) source.erase(0, source.find('\n') + 1);  // #version
  while (source.size() > 1 && source.ends_with("\n\n")) source.pop_back();
  return source;
}

}  // namespace stochtex::gl
