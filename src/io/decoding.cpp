#include "io/decoding.hpp"

#include <lcms2_plugin.h>

#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <new>
#include <type_traits>

#include "core/file_message.hpp"
#include "core/srgb.hpp"
#include "stochtex/colour.hpp"
#include "stochtex/error.hpp"

namespace stochtex {

std::vector<unsigned char> read_all(const Input& input, double max_bytes) {
  if (static_cast<double>(input.bytes) > max_bytes)
    throw Error(ErrorCode::format,
                input.name + " is " + std::to_string(input.bytes) +
                    " bytes, more than its format can hold for an image within the limits; it is "
                    "corrupt");
  std::vector<unsigned char> bytes(input.bytes);
  if (std::fseek(input.file, 0, SEEK_SET) != 0 ||
      std::fread(bytes.data(), 1, bytes.size(), input.file) != bytes.size())
    throw Error(ErrorCode::io, "cannot read " + input.name + ": " +
                                   (std::ferror(input.file) ? errno_message(errno)
                                                            : std::string("it ended early")));
  return bytes;
}

void check_size(const std::string& name, std::int64_t width, std::int64_t height,
                const ImageReadLimits& limits) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width <= 0 || height <= 0)
    throw Error(ErrorCode::format,
                name + " declares a size of " + size + " pixels; the file is corrupt");
  if (width > INT_MAX || height > INT_MAX || width > limits.max_pixels / height)
    throw Error(ErrorCode::invalid_input,
                name + " is " + size + " pixels, more than the limit of " +
                    std::to_string(limits.max_pixels) + " pixels; use a smaller image");
}

void check_declared(std::int64_t width, std::int64_t height, int channels,
                    const ImageReadLimits& limits) {
  if (limits.check_declared)
    limits.check_declared(static_cast<int>(width), static_cast<int>(height), channels);
}

void check_fits_file(const std::string& name, std::int64_t width, std::int64_t height,
                     double minimum_bytes, std::uintmax_t file_bytes) {
  if (minimum_bytes > static_cast<double>(file_bytes))
    throw Error(ErrorCode::format,
                name + " declares " + std::to_string(width) + "x" + std::to_string(height) +
                    " pixels, which need at least " +
                    std::to_string(static_cast<std::uintmax_t>(std::ceil(minimum_bytes))) +
                    " bytes, but the file has " + std::to_string(file_bytes) +
                    "; it is truncated or corrupt");
}

ImageF image_of_bytes(std::span<const unsigned char> samples, int width, int height, int channels,
                      const IccColour* icc, const char* format, ImageColour* colour) {
  ImageF image(width, height, channels);
  std::span<float> pixels = image.pixels();
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = static_cast<float>(samples[i]) / 255.0f;
  if (colour) {
    if (icc) icc->convert(image);
    colour->space = ColourSpace::srgb;
    colour->origin = icc ? icc->origin() : std::string(format) + ": sRGB by default";
  }
  return image;
}

ImageF oriented(ImageF image, int orientation) {
  if (orientation < 2 || orientation > 8) return image;
  const int width = image.width(), height = image.height(), channels = image.channels();
  // Orientations 5 to 8 exchange rows and columns.
  const bool transposed = orientation >= 5;
  ImageF result(transposed ? height : width, transposed ? width : height, channels);
  for (int y = 0; y < result.height(); ++y)
    for (int x = 0; x < result.width(); ++x) {
      // The stored pixel shown at (x, y): the tag names where the stored first row and column are
      // shown (2: first row at the top, first column on the right; 6: first row on the right,
      // first column at the top; ...).
      int sx = x, sy = y;
      switch (orientation) {
        case 2:
          sx = width - 1 - x;
          break;
        case 3:
          sx = width - 1 - x, sy = height - 1 - y;
          break;
        case 4:
          sy = height - 1 - y;
          break;
        case 5:
          sx = y, sy = x;
          break;
        case 6:
          sx = y, sy = height - 1 - x;
          break;
        case 7:
          sx = width - 1 - y, sy = height - 1 - x;
          break;
        case 8:
          sx = width - 1 - y, sy = x;
          break;
      }
      for (int c = 0; c < channels; ++c) result.at(x, y, c) = image.at(sx, sy, c);
    }
  return result;
}

// ---------------------------------------------------------------------------------------------
// ICC profiles (docs/design.md §14).

std::string printable(std::string_view text, std::size_t limit) {
  std::string result;
  for (char c : text.substr(0, limit)) result.push_back(c >= ' ' && c <= '~' ? c : '?');
  while (!result.empty() && result.back() == ' ') result.pop_back();
  if (text.size() > limit) result += "...";
  return result;
}

namespace {

// Little CMS allocates from what a profile declares (a lookup table's grid) before it reads the
// data: within the contexts below, no allocation may exceed 32 MiB, well above what a profile
// that fits in a PNG chunk (8 MiB) or a JPEG's APP2 markers (255 of 64 KiB) needs, so that a
// hostile profile is refused rather than allocated (docs/design.md §9). Little CMS handles a failed
// allocation as an error.
constexpr cmsUInt32Number kMaxIccAllocation = cmsUInt32Number{32} << 20;

void* icc_malloc(cmsContext, cmsUInt32Number size) {
  return size == 0 || size > kMaxIccAllocation ? nullptr : std::malloc(size);
}
void icc_free(cmsContext, void* pointer) {
  std::free(pointer);
}
void* icc_realloc(cmsContext, void* pointer, cmsUInt32Number size) {
  return size == 0 || size > kMaxIccAllocation ? nullptr : std::realloc(pointer, size);
}

// The allocator of Little CMS's contexts below (its memory handler plug-in, whose interface dates
// from Little CMS 2.0); cmsCreateContext takes it as a mutable pointer but only reads it.
cmsPluginMemHandler icc_memory_plugin = {
    {cmsPluginMagicNumber, 2000, cmsPluginMemHandlerSig, nullptr},
    icc_malloc,
    icc_free,
    icc_realloc,
    nullptr,
    nullptr,
    nullptr};

}  // namespace

// The first error Little CMS reports in a context, for the message that refuses the profile
// (outside the anonymous namespace: IccConversion, declared in the header, holds one).
struct IccErrors {
  char first[200] = {};
};

static void on_icc_error(cmsContext context, cmsUInt32Number, const char* text) {
  auto* errors = static_cast<IccErrors*>(cmsGetContextUserData(context));
  if (errors && !errors->first[0] && text)
    std::snprintf(errors->first, sizeof errors->first, "%s", text);
}

// An ICC profile's conversion of an image's colour channels to sRGB (the built-in sRGB profile;
// for grey, a grey profile with the sRGB tone curve), relative colorimetric, on floats, in place:
// Little CMS reads a pixel whole before it writes it, and leaves the alpha channel (an extra
// channel, without cmsFLAGS_COPY_ALPHA) as it is.
class IccConversion {
 public:
  // Refuses (throws) a profile Little CMS cannot open or turn into a transform, or whose colour
  // space is not the image's.
  IccConversion(std::span<const unsigned char> profile, int channels, const std::string& name)
      : channels_(channels) {
    context_.reset(cmsCreateContext(&icc_memory_plugin, &errors_));
    if (!context_) throw std::bad_alloc();
    cmsSetLogErrorHandlerTHR(context_.get(), on_icc_error);
    const auto refuse = [&](const std::string& problem) {
      return Error(ErrorCode::format, name + " carries an ICC profile stochtex cannot use (" +
                                          problem + "); convert the image to sRGB");
    };
    // What failed, with Little CMS's first error ("Unknown tag type 'junk' found.") but its
    // period, which would end the sentence inside the message.
    const auto icc_problem = [&](const char* what) {
      std::string problem = what;
      if (errors_.first[0]) problem += ": " + printable(errors_.first, 160);
      while (problem.back() == '.') problem.pop_back();
      return problem;
    };
    profile_.reset(cmsOpenProfileFromMemTHR(context_.get(), profile.data(),
                                            static_cast<cmsUInt32Number>(profile.size())));
    if (!profile_) throw refuse(icc_problem("Little CMS cannot open it"));
    const bool grey = channels == 1 || channels == 2;
    const cmsColorSpaceSignature space = cmsGetColorSpace(profile_.get());
    if (space == (grey ? cmsSigRgbData : cmsSigGrayData)) {
      mismatched_ = true;  // IccColour ignores it
      return;
    }
    if (space != (grey ? cmsSigGrayData : cmsSigRgbData)) {
      const auto code = static_cast<std::uint32_t>(space);
      const char signature[4] = {static_cast<char>(code >> 24), static_cast<char>(code >> 16),
                                 static_cast<char>(code >> 8), static_cast<char>(code)};
      throw refuse("its colour space is '" + printable({signature, 4}, 4) + "' and the image is " +
                   (grey ? "grey" : "RGB"));
    }
    const cmsProfileClassSignature device_class = cmsGetDeviceClass(profile_.get());
    if (device_class == cmsSigLinkClass || device_class == cmsSigAbstractClass ||
        device_class == cmsSigNamedColorClass)
      throw refuse("it is a device link, abstract or named colour profile, not an image's");
    char text[256] = {};
    cmsGetProfileInfoASCII(profile_.get(), cmsInfoDescription, "en", "US", text, sizeof text);
    text[sizeof text - 1] = '\0';
    description_ = printable(text, 64);

    if (grey) {
      // The sRGB tone curve (IEC 61966-2-1) as Little CMS's parametric curve of type 4, on sRGB's
      // white point (D65); relative colorimetric maps white to white whatever the white points.
      const cmsFloat64Number srgb_curve[5] = {2.4, 1.0 / 1.055, 0.055 / 1.055, 1.0 / 12.92,
                                              0.04045};
      const cmsCIExyY d65 = {0.3127, 0.3290, 1.0};
      cmsToneCurve* curve = cmsBuildParametricToneCurve(context_.get(), 4, srgb_curve);
      if (curve) srgb_.reset(cmsCreateGrayProfileTHR(context_.get(), &d65, curve));
      if (curve) cmsFreeToneCurve(curve);
    } else {
      srgb_.reset(cmsCreate_sRGBProfileTHR(context_.get()));
    }
    if (!srgb_) throw std::bad_alloc();
    constexpr std::array<cmsUInt32Number, 4> kFormats = {TYPE_GRAY_FLT, TYPE_GRAYA_FLT,
                                                         TYPE_RGB_FLT, TYPE_RGBA_FLT};
    const cmsUInt32Number format = kFormats[channels - 1];
    transform_.reset(cmsCreateTransformTHR(context_.get(), profile_.get(), format, srgb_.get(),
                                           format, INTENT_RELATIVE_COLORIMETRIC, 0));
    if (!transform_) throw refuse(icc_problem("Little CMS cannot convert it to sRGB"));
  }
  IccConversion(const IccConversion&) = delete;
  IccConversion& operator=(const IccConversion&) = delete;

  // Whether the profile is an RGB one and the image grey, or the other way round: a slip of paint
  // programs, which browsers and stochtex ignore. Nothing else is set then.
  bool mismatched() const { return mismatched_; }

  // The profile's description, printable, or "" when it has none.
  const std::string& description() const { return description_; }

  // Whether the profile is sRGB: it maps test colours (each channel 0, 0.02, 0.1, 0.25, 0.5,
  // 0.75, 0.9 and 1) onto themselves within 1/4096 of linear light — decided by what it does, not
  // by its name. Linear light, because the encoded values near 0 magnify every difference by
  // 12.92: Little CMS's own sRGB profile, saved (its colorants rounded to 1/65536), moves a dark
  // channel of a saturated test colour by 4.8e-4 encoded, 3.8e-5 of linear light; a gamma 2.2
  // profile moves a mid grey by 5.5e-3 of linear light.
  bool is_srgb() const {
    constexpr std::array<float, 8> kLevels = {0.0f, 0.02f, 0.1f, 0.25f, 0.5f, 0.75f, 0.9f, 1.0f};
    const int colour_channels = channels_ <= 2 ? 1 : 3;
    const std::size_t colours = colour_channels == 1 ? kLevels.size() : kLevels.size() * 64;
    std::vector<float> test(colours * channels_, 0.5f);
    for (std::size_t i = 0; i < colours; ++i)
      for (int c = 0, rest = static_cast<int>(i); c < colour_channels; ++c, rest /= 8)
        test[i * channels_ + c] = kLevels[rest % 8];
    std::vector<float> mapped(test.size(), 0.5f);
    cmsDoTransform(transform_.get(), test.data(), mapped.data(),
                   static_cast<cmsUInt32Number>(colours));
    for (std::size_t i = 0; i < test.size(); ++i)
      if (!(std::abs(srgb_decode(mapped[i]) - srgb_decode(test[i])) <= 1.0f / 4096.0f))
        return false;
    return true;
  }

  // Converts `image`'s colour channels, row by row; a value the profile makes infinite or NaN
  // (a degenerate curve) becomes 0, so that every value read stays finite.
  void convert(ImageF& image) const {
    ImageView<float> view = image.view();
    for (int y = 0; y < view.height; ++y) {
      float* row = view.row(y);
      cmsDoTransform(transform_.get(), row, row, static_cast<cmsUInt32Number>(view.width));
      for (std::ptrdiff_t i = 0; i < view.row_stride; ++i)
        if (!std::isfinite(row[i])) row[i] = 0.0f;
    }
  }

 private:
  struct DeleteContext {
    void operator()(cmsContext context) const { cmsDeleteContext(context); }
  };
  struct CloseProfile {
    void operator()(cmsHPROFILE profile) const { cmsCloseProfile(profile); }
  };
  struct DeleteTransform {
    void operator()(cmsHTRANSFORM transform) const { cmsDeleteTransform(transform); }
  };

  int channels_;
  bool mismatched_ = false;
  std::string description_;
  // Destroyed in the reverse order: the transform and profiles before their context, the context
  // before the errors it writes to; a constructor that throws destroys them too.
  IccErrors errors_;
  std::unique_ptr<std::remove_pointer_t<cmsContext>, DeleteContext> context_;
  std::unique_ptr<void, CloseProfile> profile_;
  std::unique_ptr<void, CloseProfile> srgb_;
  std::unique_ptr<void, DeleteTransform> transform_;
};

std::string mismatched_profile_origin(int channels) {
  return channels <= 2 ? "an RGB ICC profile on a grey image, ignored: sRGB by default"
                       : "a grey ICC profile on an RGB image, ignored: sRGB by default";
}

IccColour::IccColour(std::span<const unsigned char> profile, int channels, const std::string& name)
    : conversion_(std::make_unique<IccConversion>(profile, channels, name)) {
  if (conversion_->mismatched()) {
    conversion_.reset();
    origin_ = mismatched_profile_origin(channels);
    return;
  }
  const std::string named = conversion_->description().empty()
                                ? "ICC profile without a description"
                                : "ICC profile '" + conversion_->description() + "'";
  if (conversion_->is_srgb()) {
    conversion_.reset();
    origin_ = named + ": sRGB";
  } else {
    origin_ = named + ", converted to sRGB";
  }
}

IccColour::~IccColour() = default;

void IccColour::convert(ImageF& image) const {
  if (conversion_) conversion_->convert(image);
}

}  // namespace stochtex
