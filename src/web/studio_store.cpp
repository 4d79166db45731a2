#include "web/studio_store.hpp"

#include <archive.h>
#include <archive_entry.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <memory>
#include <new>
#include <optional>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "io/exemplar_region.hpp"
#include "io/image_io.hpp"
#include "model/model_data.hpp"
#include "registry.hpp"
#include "renderer/plan.hpp"
#include "report/compare.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"
#include "stochtex/io.hpp"
#include "stochtex/stochtex.hpp"
#include "web/web_export.hpp"

namespace stochtex::web {

namespace {

const std::string kUploadName = "the uploaded image";

enum class State { queued, running, done, failed, cancelled };

const char* state_name(State state) {
  switch (state) {
    case State::queued:
      return "queued";
    case State::running:
      return "running";
    case State::done:
      return "done";
    case State::failed:
      return "failed";
    case State::cancelled:
      return "cancelled";
  }
  return "failed";
}

// Thrown by the progress callback of a cancelled analysis.
struct Cancelled {};

// An image's file bytes in `format`, as the HTTP answers hold them.
std::string encode(ImageView<const float> image, ImageFormat format, int png_bit_depth = 8,
                   ColourSpace space = ColourSpace::data) {
  const std::vector<std::uint8_t> bytes = encode_image(image, format, png_bit_depth, space);
  return {bytes.begin(), bytes.end()};
}

// `entries` (name, bytes) as a zip archive, every file dated 1980-01-01 (zip's earliest time), so
// that the same export gives the same bytes.
std::string zip_archive(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string bytes;
  const std::unique_ptr<archive, decltype(&archive_write_free)> writer(archive_write_new(),
                                                                       archive_write_free);
  const auto append = [](archive*, void* client, const void* buffer, std::size_t length) {
    static_cast<std::string*>(client)->append(static_cast<const char*>(buffer), length);
    return static_cast<la_ssize_t>(length);
  };
  const auto check = [&](int status) {
    if (status != ARCHIVE_OK)
      throw StudioError(500, fmt::format("the server could not write the zip archive: {}",
                                         archive_error_string(writer.get())));
  };
  check(archive_write_set_format_zip(writer.get()));
  check(archive_write_open(writer.get(), &bytes, nullptr, append, nullptr));
  for (const auto& [name, data] : entries) {
    const std::unique_ptr<archive_entry, decltype(&archive_entry_free)> entry(archive_entry_new(),
                                                                              archive_entry_free);
    archive_entry_set_pathname(entry.get(), name.c_str());
    archive_entry_set_size(entry.get(), static_cast<la_int64_t>(data.size()));
    archive_entry_set_filetype(entry.get(), AE_IFREG);
    archive_entry_set_perm(entry.get(), 0644);
    archive_entry_set_mtime(entry.get(), 315532800, 0);
    check(archive_write_header(writer.get(), entry.get()));
    if (archive_write_data(writer.get(), data.data(), data.size()) !=
        static_cast<la_ssize_t>(data.size()))
      check(ARCHIVE_FATAL);
  }
  check(archive_write_close(writer.get()));
  return bytes;
}

template <typename Map>
void evict_oldest(Map& map, std::deque<std::string>& order, std::size_t keep) {
  while (order.size() > keep) {
    map.erase(order.front());
    order.pop_front();
  }
}

// Entry `id` of `map` (a store kept to its last `keep` entries; the caller holds the store's
// lock), or a 404 that names the `kind` of entry and what to do.
template <typename Map>
typename Map::mapped_type find_kept(const Map& map, const std::string& id, std::string_view kind,
                                    std::size_t keep, std::string_view remedy) {
  const auto found = map.find(id);
  if (found == map.end())
    throw StudioError(404, fmt::format("there is no {} '{}' (the studio keeps the last {}); {}",
                                       kind, id, keep, remedy));
  return found->second;
}

}  // namespace

struct StudioStore::Exemplar {
  ImageF image;
  // What the upload's values are, as `analyze --colour-space auto` reads a file (a PNG is sRGB
  // unless its chunks say otherwise, OpenEXR linear): its models render linear light.
  ImageColour colour;
  // The stored values, where reading the colour changed them (a gAMA or an ICC profile other
  // than sRGB): what an analysis as data takes, as `analyze --colour-space data` reads the file.
  std::optional<ImageF> stored;
  std::string png;
  mutable std::string gaussian_png;  // filled once, under heavy_
};

struct StudioStore::Analysis {
  std::string id;
  std::string client;
  std::shared_ptr<const Exemplar> exemplar;
  std::string method;
  std::string reason;  // --method auto's one line, where "auto" chose the method
  ParamValues params;
  std::uint32_t seed = 0;
  bool data = false;  // analysed as data: the stored values, no colour
  std::atomic<State> state{State::queued};
  std::atomic<double> progress{0.0};
  std::atomic<bool> cancel{false};
  std::chrono::steady_clock::time_point started;
  double seconds = 0.0;  // the analysis' time, once finished (guarded by mutex_)
  std::string error;     // guarded by mutex_
  std::string model;     // guarded by mutex_
};

struct StudioStore::StoredModel {
  StoredModel(Model stored, std::shared_ptr<const Exemplar> source)
      : model(std::move(stored)), exemplar(std::move(source)) {}
  Model model;
  std::shared_ptr<const Exemplar> exemplar;
  // The web exports made so far, by ShaderVariant; guarded by web_mutex.
  mutable std::mutex web_mutex;
  mutable std::array<std::vector<WebFile>, 2> web;
  // The model's groups for its edit capability (EditCapability::find_groups), found once;
  // guarded by groups_mutex.
  mutable std::mutex groups_mutex;
  mutable std::shared_ptr<const void> groups;
};

StudioStore::StudioStore(StudioLimits limits) : limits_(limits) {
  worker_ = std::thread([this] { work(); });
}

StudioStore::~StudioStore() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (const auto& [id, analysis] : analyses_) analysis->cancel = true;
  }
  wake_.notify_all();
  worker_.join();
}

std::string StudioStore::new_id() {
  // 64 bits of the system's random source: an id tells nothing of another, so that only whoever
  // was given an id reaches what it names.
  for (;;) {
    std::string id = fmt::format("{:08x}{:08x}", random_(), random_());
    if (!exemplars_.contains(id) && !analyses_.contains(id) && !models_.contains(id)) return id;
  }
}

nlohmann::ordered_json StudioStore::add_exemplar(const std::string& bytes) {
  if (bytes.size() > limits_.max_upload_bytes)
    throw StudioError(413, fmt::format("the upload is {} bytes, more than the limit of {} bytes; "
                                       "upload a smaller image",
                                       bytes.size(), limits_.max_upload_bytes));
  auto exemplar = std::make_shared<Exemplar>();
  std::string note;
  try {
    const std::span<const std::uint8_t> file(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                             bytes.size());
    const ImageReadLimits limits{.max_pixels = limits_.max_upload_pixels, .check_declared = {}};
    // A photo larger than the studio's exemplars is downscaled in linear light, and the answer
    // says so (io/exemplar_region.hpp).
    const auto fitted = [&](ImageF image, ColourSpace space, std::string* said) {
      return exemplar_region(std::move(image), space, {}, limits_.max_exemplar_side, kUploadName,
                             "the studio", said);
    };
    exemplar->image = fitted(decode_image(file, kUploadName, limits, &exemplar->colour),
                             exemplar->colour.space, &note);
    ImageF stored =
        fitted(decode_image(file, kUploadName, limits), exemplar->colour.space, nullptr);
    if (!std::ranges::equal(stored.pixels(), exemplar->image.pixels()))
      exemplar->stored = std::move(stored);
    validate_exemplar(exemplar->image.view(), kUploadName);
    if (!note.empty()) note += "; crop the photo first to keep its finest detail";
  } catch (const Error& e) {
    throw StudioError(400, e.what());
  }
  {
    const std::lock_guard heavy(heavy_);
    exemplar->png = encode(exemplar->image.view(), ImageFormat::png, 8, exemplar->colour.space);
  }
  std::lock_guard lock(mutex_);
  const std::string id = new_id();
  const nlohmann::ordered_json info{{"id", id},
                                    {"width", exemplar->image.width()},
                                    {"height", exemplar->image.height()},
                                    {"channels", exemplar->image.channels()},
                                    {"colour_space", colour_space_name(exemplar->colour.space)},
                                    {"colour", exemplar->colour.origin},
                                    {"note", note}};
  exemplars_[id] = std::move(exemplar);
  exemplar_order_.push_back(id);
  evict_oldest(exemplars_, exemplar_order_, limits_.max_exemplars);
  return info;
}

std::shared_ptr<const StudioStore::Exemplar> StudioStore::find_exemplar(const std::string& id) {
  std::lock_guard lock(mutex_);
  return find_kept(exemplars_, id, "exemplar", limits_.max_exemplars, "upload it again");
}

std::string StudioStore::exemplar_png(const std::string& id, bool gaussian) {
  const auto exemplar = find_exemplar(id);
  if (!gaussian) return exemplar->png;
  const std::lock_guard heavy(heavy_);
  std::string& cached = exemplar->gaussian_png;
  if (cached.empty()) {
    const ImageView<const float> image = exemplar->image.view();
    const ImageF version = gaussian_version(image, image.width, image.height, 1);
    cached = encode(version.view(), ImageFormat::png, 8, exemplar->colour.space);
  }
  return cached;
}

std::string StudioStore::start_analysis(const std::string& client, const std::string& exemplar,
                                        const std::string& method,
                                        const nlohmann::ordered_json& params, std::uint32_t seed,
                                        const std::string& colour_space) {
  if (colour_space != "auto" && colour_space != "data")
    throw StudioError(400, fmt::format("\"colour_space\" is auto (what the upload says) or data "
                                       "(its values as they are), not '{}'",
                                       colour_space));
  if (!params.is_object())
    throw StudioError(400, "\"params\" must be an object of parameter names and values");
  std::map<std::string, std::string, std::less<>> text;
  for (const auto& [name, value] : params.items()) {
    if (value.is_string())
      text[name] = value.get<std::string>();
    else if (value.is_number_integer())
      text[name] = fmt::format("{}", value.get<std::int64_t>());
    else if (value.is_number())
      text[name] = fmt::format("{}", value.get<double>());
    else
      throw StudioError(
          400, fmt::format("the parameter '{}' must be a number or a choice's name", name));
  }
  auto analysis = std::make_shared<Analysis>();
  analysis->data = colour_space == "data";
  analysis->exemplar = find_exemplar(exemplar);
  analysis->method = method;
  // "auto" (`--method auto`): the method chosen from the values the analysis will read.
  const Exemplar& source = *analysis->exemplar;
  const ImageF& image = analysis->data && source.stored ? *source.stored : source.image;
  if (method == kAutoMethod) {
    if (!text.empty())
      throw StudioError(400,
                        "\"params\" set a named method's parameters, and \"auto\" chooses "
                        "the method from the exemplar: send the method with them");
    const MethodChoice choice = choose_method(image.view());
    analysis->method = choice.method;
    analysis->reason = choice.reason;
  }
  // The registry refuses what it cannot analyse before any work, as `stochtex analyze` does: a
  // method without a row of its own (one not analysed from one exemplar, such as a mix), more
  // channels than the method takes, or beyond the memory budget.
  try {
    check_analysis_request(analysis->method, image.width(), image.height(), image.channels(),
                           kUploadName);
    analysis->params = resolve_params(analysis->method, text);
  } catch (const std::invalid_argument& e) {
    throw StudioError(400, e.what());
  } catch (const Error& e) {
    throw StudioError(400, e.what());
  }
  analysis->client = client;
  analysis->seed = seed;
  std::lock_guard lock(mutex_);
  for (const auto& [id, other] : analyses_)
    if (other->client == client &&
        (other->state == State::queued || other->state == State::running))
      throw StudioError(429,
                        "this browser already has an analysis queued or running; wait for "
                        "it to finish or cancel it first");
  if (queue_.size() >= limits_.max_queued)
    throw StudioError(503, fmt::format("the analysis queue is full ({} waiting); try again when "
                                       "one has finished",
                                       queue_.size()));
  analysis->id = new_id();
  analyses_[analysis->id] = analysis;
  analysis_order_.push_back(analysis->id);
  queue_.push_back(analysis);
  evict_analyses();
  wake_.notify_all();
  return analysis->id;
}

void StudioStore::evict_analyses() {
  // The oldest finished records go first; queued and running ones stay (the queue bounds them).
  for (auto it = analysis_order_.begin();
       analysis_order_.size() > limits_.max_analyses && it != analysis_order_.end();) {
    const State state = analyses_.at(*it)->state;
    if (state == State::queued || state == State::running) {
      ++it;
      continue;
    }
    analyses_.erase(*it);
    it = analysis_order_.erase(it);
  }
}

nlohmann::ordered_json StudioStore::analysis_status(const std::string& id) {
  std::lock_guard lock(mutex_);
  const auto found = analyses_.find(id);
  if (found == analyses_.end())
    throw StudioError(404, fmt::format("there is no analysis '{}'; start one first", id));
  const Analysis& analysis = *found->second;
  const State state = analysis.state;
  double seconds = analysis.seconds;
  if (state == State::running)
    seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - analysis.started).count();
  nlohmann::ordered_json status{{"id", analysis.id},
                                {"method", analysis.method},
                                {"state", state_name(state)},
                                {"progress", state == State::done ? 1.0 : analysis.progress.load()},
                                {"seconds", seconds}};
  if (!analysis.reason.empty()) {
    status["chosen_by"] = kAutoMethod;
    status["reason"] = analysis.reason;
  }
  if (state == State::failed) status["error"] = analysis.error;
  if (state == State::done) status["model"] = analysis.model;
  return status;
}

nlohmann::ordered_json StudioStore::cancel_analysis(const std::string& id,
                                                    const std::string& client) {
  {
    std::lock_guard lock(mutex_);
    const auto found = analyses_.find(id);
    if (found == analyses_.end())
      throw StudioError(404, fmt::format("there is no analysis '{}'; start one first", id));
    Analysis& analysis = *found->second;
    if (analysis.client != client)
      throw StudioError(403, "this analysis was started by another browser; only it can cancel it");
    analysis.cancel = true;
    if (analysis.state == State::queued) {
      analysis.state = State::cancelled;
      std::erase(queue_, found->second);
    }
  }
  return analysis_status(id);
}

void StudioStore::work() {
  for (;;) {
    std::shared_ptr<Analysis> analysis;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      analysis = queue_.front();
      queue_.pop_front();
      analysis->started = std::chrono::steady_clock::now();
      analysis->state = State::running;
    }
    run(*analysis);
  }
}

void StudioStore::run(Analysis& analysis) {
  State state = State::done;
  std::string error;
  Model model;
  try {
    // As data: the values as stored, which reading the colour may have converted.
    const Exemplar& exemplar = *analysis.exemplar;
    const ImageF& values = analysis.data && exemplar.stored ? *exemplar.stored : exemplar.image;
    model = analyze(
        analysis.method, values.view(), analysis.params, analysis.seed, kUploadName,
        [&analysis](double fraction) {
          if (analysis.cancel) throw Cancelled{};
          analysis.progress = fraction;
        },
        analysis.data ? ColourSpace::data : exemplar.colour.space);
  } catch (const Cancelled&) {
    state = State::cancelled;
  } catch (const std::bad_alloc&) {
    state = State::failed;
    error = "the analysis ran out of memory; use a smaller exemplar";
  } catch (const std::exception& e) {
    state = State::failed;
    error = e.what();
  }
  std::lock_guard lock(mutex_);
  analysis.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - analysis.started).count();
  analysis.error = error;
  if (state == State::done) {
    analysis.model = new_id();
    models_[analysis.model] =
        std::make_shared<const StoredModel>(std::move(model), analysis.exemplar);
    model_order_.push_back(analysis.model);
    evict_oldest(models_, model_order_, limits_.max_models);
  }
  analysis.exemplar.reset();
  analysis.state = state;
}

std::shared_ptr<const StudioStore::StoredModel> StudioStore::find_model(const std::string& id) {
  std::lock_guard lock(mutex_);
  return find_kept(models_, id, "model", limits_.max_models, "run the analysis again");
}

Model StudioStore::model(const std::string& id) {
  return find_model(id)->model;
}

std::string StudioStore::model_file(const std::string& id) {
  const std::vector<std::uint8_t> bytes = serialize_model(model(id));
  return {bytes.begin(), bytes.end()};
}

std::pair<const EditCapability*, std::shared_ptr<const void>> StudioStore::edit_groups(
    const StoredModel& stored, const std::string& id) {
  const EditCapability* edit = edit_capability(stored.model.method());
  if (edit == nullptr)
    throw StudioError(400,
                      fmt::format("model '{}' is a {} model; only {} models have groups to "
                                  "edit (run a {} analysis)",
                                  id, stored.model.method(), methods_with(CapabilityKind::edit),
                                  methods_with(CapabilityKind::edit)));
  std::lock_guard lock(stored.groups_mutex);
  if (!stored.groups) stored.groups = edit->find_groups(stored.model);
  return {edit, stored.groups};
}

nlohmann::ordered_json StudioStore::edit_groups(const std::string& id) {
  const std::shared_ptr<const StoredModel> stored = find_model(id);
  const auto [edit, groups] = edit_groups(*stored, id);
  return edit->groups_json(stored->model, groups.get());
}

std::string StudioStore::edit_model(const std::string& id, const nlohmann::ordered_json& body) {
  const std::shared_ptr<const StoredModel> stored = find_model(id);
  const auto [edit, groups] = edit_groups(*stored, id);
  std::optional<Model> edited;
  try {
    const EditValues values = edit_values_from_json(*edit, body);
    const std::lock_guard heavy(heavy_);
    edited.emplace(edit->edit(stored->model, groups.get(), values, "").model);
  } catch (const std::invalid_argument& e) {
    throw StudioError(400, e.what());
  }
  std::lock_guard lock(mutex_);
  const std::string edited_id = new_id();
  models_[edited_id] = std::make_shared<const StoredModel>(std::move(*edited), stored->exemplar);
  edited_order_.push_back(edited_id);
  evict_oldest(models_, edited_order_, limits_.max_edited_models);
  return edited_id;
}

std::string StudioStore::web_file(const std::string& id, ShaderVariant variant,
                                  const std::string& name) {
  const std::shared_ptr<const StoredModel> stored = find_model(id);
  std::lock_guard lock(stored->web_mutex);
  std::vector<WebFile>& files = stored->web[static_cast<std::size_t>(variant)];
  if (files.empty()) {
    std::lock_guard heavy(heavy_);
    try {
      files = web_export(stored->model, variant);
    } catch (const std::invalid_argument& e) {
      throw StudioError(422, e.what());
    } catch (const Error& e) {
      throw StudioError(422, e.what());
    }
  }
  for (const WebFile& file : files)
    if (file.name == name) return file.bytes;
  throw StudioError(404, fmt::format("the web export of model '{}' has no file '{}'", id, name));
}

std::string StudioStore::shader_zip(const std::string& id, const ShaderExportOptions& options) {
  const std::shared_ptr<const StoredModel> stored = find_model(id);
  std::lock_guard heavy(heavy_);
  ShaderExport files;
  try {
    files = export_shader(stored->model, options);
  } catch (const std::invalid_argument& e) {
    throw StudioError(422, e.what());
  } catch (const Error& e) {
    throw StudioError(422, e.what());
  }
  std::vector<std::pair<std::string, std::string>> entries = {
      {files.shader.name, files.shader.text}};
  for (const TextFile& wrapper : files.wrappers) entries.emplace_back(wrapper.name, wrapper.text);
  for (const ShaderTexture& texture : files.textures) {
    const std::string name = texture.file_name();
    entries.emplace_back(name, encode(texture.image.view(), output_image_format(name),
                                      texture.encoding == TextureEncoding::png16 ? 16 : 8));
  }
  entries.emplace_back("README.md", files.readme);
  entries.emplace_back("manifest.json", files.manifest);
  return zip_archive(entries);
}

std::string StudioStore::render_png(const std::string& id, const RenderRequest& request) {
  const int most = limits_.max_render_side;
  if (request.width < 1 || request.height < 1 || request.width > most || request.height > most)
    throw StudioError(400, fmt::format("a render is 1 to {} pixels wide and high, not {}x{}; ask "
                                       "for a smaller one",
                                       most, request.width, request.height));
  if (!(request.scale >= renderer::kMinScale && request.scale <= renderer::kMaxScale))
    throw StudioError(400,
                      fmt::format("a render's scale is {:g} to {:g} exemplar pixels per pixel, "
                                  "as `stochtex render --scale` takes, not {:g}",
                                  renderer::kMinScale, renderer::kMaxScale, request.scale));
  const auto stored = find_model(id);
  const Grid grid{request.origin, request.scale, request.width, request.height};
  // As many cores as the memory budget allows, as `stochtex render --threads 0` takes; a view of
  // at most max_render_side squared pixels is far within it.
  RenderOptions options;
  try {
    check_grid(grid, "the render's view");
    options.threads = renderer::budgeted_threads(
        request.width, request.height, options.tile_size, options.supersample, 0,
        [&](int threads) {
          return fmt::format("rendering {}x{} pixels on {} threads", request.width, request.height,
                             threads);
        },
        "ask for a smaller one", stored->model.channels());
  } catch (const std::invalid_argument& e) {
    throw StudioError(400, e.what());
  }
  const std::lock_guard heavy(heavy_);
  ImageF image(request.width, request.height, stored->model.channels());
  render(stored->model, grid, request.seed, image.view(), options);
  return encode(image.view(), ImageFormat::png, 8, rendered_space(stored->model.colour_space()));
}

nlohmann::ordered_json StudioStore::compare(const std::string& id, std::uint32_t seed) {
  const auto stored = find_model(id);
  // A model of data was analysed from the stored values (start_analysis).
  const bool data = stored->model.colour_space() == ColourSpace::data;
  const ImageView<const float> exemplar =
      (data && stored->exemplar->stored ? *stored->exemplar->stored : stored->exemplar->image)
          .view();
  const std::lock_guard heavy(heavy_);
  ImageF image(exemplar.width, exemplar.height, stored->model.channels());
  render(stored->model, Grid{{0.0, 0.0}, 1.0, exemplar.width, exemplar.height}, seed, image.view());
  // The exemplar's values are sRGB-encoded where the render's are linear light: compared encoded.
  if (stored->model.colour_space() == ColourSpace::srgb) encode_colour_channels(image.view());
  Comparison comparison(exemplar);
  try {
    add_checked(comparison, exemplar, "the exemplar", image.view(), "the render");
  } catch (const Error& e) {
    throw StudioError(422, e.what());
  }
  nlohmann::ordered_json doc{{"model", id}, {"seed", seed}};
  doc.update(comparison_json(comparison.report()));
  return doc;
}

}  // namespace stochtex::web
