// View transforms through OpenColorIO, with the Standard sRGB view built in so that it is exact.
#include "image/display_transform.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "base/error.h"
#include "image/image_io.h"

namespace OCIO = OCIO_NAMESPACE;

namespace dp {

namespace {

constexpr const char* kBlenderConfig = "/usr/share/blender/datafiles/colormanagement/config.ocio";

/// The config, loaded once per process (OpenColorIO configs are immutable once read).
OCIO::ConstConfigRcPtr config() {
    static std::once_flag once;
    static OCIO::ConstConfigRcPtr loaded;
    std::call_once(once, [] {
        const std::string path = ocio_config_path();
        if (path.empty()) return;
        try {
            loaded = OCIO::Config::CreateFromFile(path.c_str());
        } catch (const OCIO::Exception&) {
            loaded = nullptr;  // a broken config offers no views; Standard still works
        }
    });
    return loaded;
}

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "\"" : ", \"") + n + "\"";
    return out;
}

}  // namespace

std::string ocio_config_path() {
    std::error_code ec;
    if (const char* env = std::getenv("OCIO"); env && *env && std::filesystem::is_regular_file(env, ec)) return env;
    if (std::filesystem::is_regular_file(kBlenderConfig, ec)) return kBlenderConfig;
    return "";
}

std::vector<std::string> available_views() {
    std::vector<std::string> views = {"Standard", "Raw"};
    if (const auto c = config()) {
        const char* display = c->getDefaultDisplay();
        for (int i = 0; i < c->getNumViews(display); ++i) {
            const std::string v = c->getView(display, i);
            if (std::find(views.begin(), views.end(), v) == views.end()) views.push_back(v);
        }
    }
    return views;
}

std::vector<std::string> available_looks() {
    std::vector<std::string> looks;
    if (const auto c = config())
        for (int i = 0; i < c->getNumLooks(); ++i) looks.emplace_back(c->getLookNameByIndex(i));
    return looks;
}

void convert_colorspace_to_linear(Image& image, const std::string& space, const std::string& field) {
    const auto c = config();
    if (!c)
        throw InputError("", field,
                         "colour space \"" + space +
                             "\" needs an OpenColorIO config ($OCIO or Blender's); only \"srgb\" and \"linear\" "
                             "are built in");
    if (!c->getColorSpace(space.c_str())) {
        std::vector<std::string> names;
        for (int i = 0; i < c->getNumColorSpaces(); ++i) names.emplace_back(c->getColorSpaceNameByIndex(i));
        throw InputError("", field,
                         "unknown colour space \"" + space + "\"; the config (" + ocio_config_path() +
                             ") has: srgb, linear, " + join(names));
    }
    if (image.empty()) return;
    try {
        const auto cpu = c->getProcessor(space.c_str(), OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor();
        OCIO::PackedImageDesc desc(image.data(), image.width(), image.height(), 3);
        cpu->apply(desc);
    } catch (const OCIO::Exception& e) {
        throw InputError("", field, "cannot convert from \"" + space + "\": " + e.what());
    }
}

struct DisplayTransform::Processor {
    OCIO::ConstCPUProcessorRcPtr cpu;
};

DisplayTransform::DisplayTransform(const ViewSettings& settings) : settings_(settings) {
    if (!std::isfinite(settings.exposure)) throw InputError("", "exposure", "must be a finite number of stops");
    const bool built_in = settings.view == "Standard" || settings.view == "Raw";
    const auto c = config();
    std::string look_name = settings.look;
    if (!look_name.empty()) {
        const std::vector<std::string> looks = available_looks();
        auto known = [&](const std::string& n) { return std::find(looks.begin(), looks.end(), n) != looks.end(); };
        // Blender's menu shows a look with its view's name before it ("Filmic - High Contrast")
        // where the config names it alone ("High Contrast"): both spellings are taken.
        const std::string prefix = settings.view + " - ";
        if (!known(look_name) && look_name.rfind(prefix, 0) == 0 && known(look_name.substr(prefix.size())))
            look_name = look_name.substr(prefix.size());
        if (!known(look_name))
            throw InputError("", "look",
                             "unknown look \"" + settings.look + "\"" +
                                 (looks.empty() ? std::string(" (no OpenColorIO config offers looks)")
                                                : "; choose one of " + join(looks)));
    }
    if (built_in && settings.look.empty()) return;
    const std::vector<std::string> views = available_views();
    if (std::find(views.begin(), views.end(), settings.view) == views.end())
        throw InputError("", "view", "unknown view \"" + settings.view + "\"; choose one of " + join(views));
    try {
        auto group = OCIO::GroupTransform::Create();
        if (!settings.look.empty()) {
            auto look = OCIO::LookTransform::Create();
            look->setSrc(OCIO::ROLE_SCENE_LINEAR);
            look->setDst(OCIO::ROLE_SCENE_LINEAR);
            look->setLooks(look_name.c_str());
            group->appendTransform(look);
        }
        auto view = OCIO::DisplayViewTransform::Create();
        view->setSrc(OCIO::ROLE_SCENE_LINEAR);
        view->setDisplay(c->getDefaultDisplay());
        view->setView(settings.view.c_str());
        group->appendTransform(view);
        processor_ = std::make_unique<Processor>();
        processor_->cpu = c->getProcessor(group)->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
        throw InputError("", "view", "cannot build view \"" + settings.view + "\": " + e.what());
    }
}

DisplayTransform::~DisplayTransform() = default;
DisplayTransform::DisplayTransform(DisplayTransform&&) noexcept = default;
DisplayTransform& DisplayTransform::operator=(DisplayTransform&&) noexcept = default;

void DisplayTransform::apply(const vec3* in, vec3* out, size_t n) const {
    const float scale = std::exp2(settings_.exposure);
    auto clamp01 = [](float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f); };
    if (!processor_) {
        const bool curve = settings_.view == "Standard";
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                const float v = clamp01(in[i][c] * scale);
                out[i][c] = curve ? linear_to_srgb(v) : v;
            }
        return;
    }
    for (size_t i = 0; i < n; ++i) {
        out[i] = in[i] * scale;
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(out[i][c])) out[i][c] = 0;  // a LUT would spread NaN to its neighbours
    }
    // Rows of at most 2^20 pixels: PackedImageDesc's sizes are longs, but its processors tile.
    constexpr size_t kChunk = size_t(1) << 20;
    for (size_t begin = 0; begin < n; begin += kChunk) {
        const long count = long(std::min(kChunk, n - begin));
        OCIO::PackedImageDesc desc(&out[begin].x, count, 1, 3);
        processor_->cpu->apply(desc);
    }
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out[i][c] = clamp01(out[i][c]);
}

Image DisplayTransform::apply(const Image& linear) const {
    Image out(linear.width(), linear.height());
    apply(linear.data(), out.data(), linear.size());
    return out;
}

}  // namespace dp
