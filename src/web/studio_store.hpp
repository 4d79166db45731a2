#pragma once
// What `stochtex studio` holds (docs/studio.md): the uploaded exemplars, the analyses (run one at
// a time by one worker thread, from a bounded queue, at most one queued or running per browser
// client) and the models they made, each kept up to a count and the oldest evicted. Images and
// models are decoded and encoded in memory: the store writes no file, and nothing from a request
// names one. Every failure is a StudioError: an HTTP status and one sentence for the JSON error
// body.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "methods/capabilities.hpp"
#include "stochtex/gpu.hpp"
#include "stochtex/image.hpp"
#include "stochtex/model.hpp"

namespace stochtex::web {

struct StudioLimits {
  std::size_t max_upload_bytes = std::size_t{16} << 20;  // an upload's body, 16 MiB
  std::int64_t max_upload_pixels = 24'000'000;           // an upload's pixels: a 6000x4000 photo
  int max_exemplar_side = 1024;  // an exemplar's longer side: a larger upload is downscaled to it
  std::size_t max_exemplars = 8;
  std::size_t max_models = 8;         // analysed models
  std::size_t max_edited_models = 4;  // edited ones, evicted among themselves
  std::size_t max_analyses = 64;      // analysis records kept (finished ones evicted first)
  std::size_t max_queued = 4;         // analyses waiting behind the running one
  int max_render_side = 2048;         // render.png's width and height
};

class StudioError : public std::runtime_error {
 public:
  StudioError(int status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// A CPU render of a model: output pixel (i, j) samples origin + scale * (i + 1/2, j + 1/2), as
// `stochtex render --origin X,Y --scale S --seed SEED`.
struct RenderRequest {
  int width = 512;
  int height = 512;
  std::uint32_t seed = 0;
  double scale = 1.0;
  Vec2d origin;
};

class StudioStore {
 public:
  explicit StudioStore(StudioLimits limits);
  ~StudioStore();  // cancels the running analysis and stops the worker
  StudioStore(const StudioStore&) = delete;
  StudioStore& operator=(const StudioStore&) = delete;

  const StudioLimits& limits() const { return limits_; }

  // An image file's bytes (PNG, OpenEXR, PFM) -> {"id", "width", "height", "channels"}.
  nlohmann::ordered_json add_exemplar(const std::string& bytes);
  // The exemplar, or its Gaussian version (ADSN at its size, seed 1), as PNG bytes.
  std::string exemplar_png(const std::string& id, bool gaussian);

  // Queues an analysis of exemplar `exemplar` for `client`; `params` maps names to numbers or
  // choice names; `colour_space` is analyze's --colour-space (auto: what the upload says; data:
  // its stored values, as they are). `method` "auto" (kAutoMethod) is chosen here by
  // choose_method, before the queue, and takes no `params`. Returns its id.
  std::string start_analysis(const std::string& client, const std::string& exemplar,
                             const std::string& method, const nlohmann::ordered_json& params,
                             std::uint32_t seed, const std::string& colour_space = "auto");
  // {"id", "method", "state", "progress", "seconds", "chosen_by"?, "reason"?, "error"?,
  // "model"?}: "chosen_by": "auto" and the choice's one-line "reason" where auto chose "method".
  nlohmann::ordered_json analysis_status(const std::string& id);
  // Cancels `client`'s queued or running analysis (a finished one is left as it is); its status.
  // Another client's analysis is a 403.
  nlohmann::ordered_json cancel_analysis(const std::string& id, const std::string& client);

  // The model `id` (a 404 when the store has none such), for routes that serve what is made from
  // it.
  Model model(const std::string& id);
  std::string model_file(const std::string& id);  // the .stx bytes
  std::string render_png(const std::string& id, const RenderRequest& request);
  // `stochtex compare --json`'s numbers of a render at the exemplar's size against the exemplar.
  nlohmann::ordered_json compare(const std::string& id, std::uint32_t seed);
  // The groups of the model `id` (its registry row's edit capability: `stochtex edit --list-groups
  // --json`); a 400 for a method that has none.
  nlohmann::ordered_json edit_groups(const std::string& id);
  // Edits the model `id` as `stochtex edit` does, from the JSON edit `body` (registry.hpp,
  // edit_values_from_json), and stores the result as a new model (made from the same exemplar);
  // its id. A 400 for a method without the capability or a bad edit.
  std::string edit_model(const std::string& id, const nlohmann::ordered_json& body);

  // The file `name` of the model's web export in `variant` (web_export.hpp: what the viewer
  // loads), made once per model and variant; a 404 for a name the export does not have.
  std::string web_file(const std::string& id, ShaderVariant variant, const std::string& name);
  // `stochtex export-shader`'s files of the model (the shader, its wrappers, the data images and
  // README.md) as one zip archive; a 422 for what the export refuses (gabor's exact shader
  // outside GLSL, a model of more than 4 channels).
  std::string shader_zip(const std::string& id, const ShaderExportOptions& options);

 private:
  struct Exemplar;
  struct Analysis;
  struct StoredModel;

  std::shared_ptr<const Exemplar> find_exemplar(const std::string& id);
  std::shared_ptr<const StoredModel> find_model(const std::string& id);
  // The stored model `id`'s edit capability and its groups, found once; a 400 for a method that
  // has none.
  std::pair<const EditCapability*, std::shared_ptr<const void>> edit_groups(
      const StoredModel& stored, const std::string& id);
  std::string new_id();
  void work();
  void run(Analysis& analysis);
  void evict_analyses();

  StudioLimits limits_;
  std::mutex mutex_;  // guards everything below but the heavy-work mutex
  std::condition_variable wake_;
  bool stopping_ = false;
  std::random_device random_;  // the ids' bits
  std::map<std::string, std::shared_ptr<const Exemplar>> exemplars_;
  std::deque<std::string> exemplar_order_;
  std::map<std::string, std::shared_ptr<Analysis>> analyses_;
  std::deque<std::string> analysis_order_;
  std::deque<std::shared_ptr<Analysis>> queue_;
  std::map<std::string, std::shared_ptr<const StoredModel>> models_;
  std::deque<std::string> model_order_;
  std::deque<std::string> edited_order_;
  std::mutex heavy_;  // one render, Gaussian version or comparison at a time: bounded memory
  std::thread worker_;
};

}  // namespace stochtex::web
