// FontSet: the fallback chain. Each file is opened once through FreeType
// (freetype_faces.cpp) to read its names and character map, then closed: the
// chain keeps sorted code point lists, so font_for() is a few binary searches
// and the set is immutable (safe to share between threads). Renderers open
// their own faces from path().
#include "text/font_set.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "freetype_faces.hpp"

namespace globe::text {

struct FontSet::Impl {
  std::vector<std::string> paths;
  std::vector<std::string> families, styles;
  std::vector<std::vector<char32_t>> coverage;  // per font, ascending
};

FontSet FontSet::debian(const std::string& first, bool bold) {
  const std::string noto = "/usr/share/fonts/truetype/noto/";
  const std::string dejavu = "/usr/share/fonts/truetype/dejavu/";
  const std::string weight = bold ? "-Bold.ttf" : "-Regular.ttf";
  std::vector<std::string> paths;
  if (!first.empty()) {
    if (!std::ifstream(first).good()) {
      throw TextError(first + ": cannot read the label font; check the path of --label-font");
    }
    paths.push_back(first);
  }
  for (const char* script : {"", "Arabic", "Hebrew", "Devanagari", "Bengali", "Thai", "Georgian",
                             "Armenian", "Ethiopic"}) {
    paths.push_back(noto + "NotoSans" + script + weight);
  }
  paths.push_back(dejavu + (bold ? "DejaVuSans-Bold.ttf" : "DejaVuSans.ttf"));
  std::vector<std::string> found;
  for (size_t i = 0; i < paths.size(); ++i) {
    std::error_code error;
    if ((!first.empty() && i == 0) || std::filesystem::is_regular_file(paths[i], error)) {
      found.push_back(paths[i]);
    }
  }
  if (found.empty()) {
    throw TextError("no label fonts in " + noto + " or " + dejavu +
                    "; install fonts-noto-core and fonts-dejavu-core, or pass --label-font");
  }
  return FontSet(std::move(found));
}

FontSet::FontSet(std::vector<std::string> paths) : impl_(std::make_unique<Impl>()) {
  if (paths.empty()) throw TextError("FontSet: no font files given");
  detail::FreetypeFaces faces(paths);
  for (size_t i = 0; i < faces.size(); ++i) {
    impl_->families.push_back(faces.family(i));
    impl_->styles.push_back(faces.style(i));
    impl_->coverage.push_back(faces.code_points(i));
  }
  impl_->paths = std::move(paths);
}

FontSet::~FontSet() = default;
FontSet::FontSet(FontSet&&) noexcept = default;
FontSet& FontSet::operator=(FontSet&&) noexcept = default;

size_t FontSet::size() const {
  return impl_->paths.size();
}
const std::string& FontSet::path(size_t font) const {
  return impl_->paths.at(font);
}
std::string FontSet::family(size_t font) const {
  return impl_->families.at(font);
}
std::string FontSet::style(size_t font) const {
  return impl_->styles.at(font);
}

bool FontSet::has(size_t font, char32_t c) const {
  const std::vector<char32_t>& cps = impl_->coverage.at(font);
  return std::binary_search(cps.begin(), cps.end(), c);
}

int FontSet::font_for(char32_t c) const {
  for (size_t i = 0; i < impl_->coverage.size(); ++i) {
    if (has(i, c)) return static_cast<int>(i);
  }
  return -1;
}

std::string FontSet::fontstack_name() const {
  // node-fontnik's name of a face: family_name + " " + style_name.
  const std::string& style = impl_->styles.front();
  return style.empty() ? impl_->families.front() : impl_->families.front() + " " + style;
}

}  // namespace globe::text
