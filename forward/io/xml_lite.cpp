#include "forward/io/xml_lite.hpp"

#include <cctype>

namespace ddafit::io {

const std::string* XmlElement::attribute(const std::string& key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

namespace {

std::string local_name(const std::string& name) {
  const size_t colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& label) : s_(text), label_(label) {}

  XmlElement document() {
    skip_misc();
    if (!starts("<")) fail("no root element");
    XmlElement root = element();
    skip_misc();
    if (at_ < s_.size()) fail("text after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw XmlError(label_ + ": line " + std::to_string(line_) + ": " + why);
  }
  bool starts(const char* p) const { return s_.compare(at_, std::char_traits<char>::length(p), p) == 0; }
  void advance(size_t n) {
    for (size_t k = 0; k < n && at_ < s_.size(); ++k, ++at_)
      if (s_[at_] == '\n') ++line_;
  }
  void skip_to(const char* end, const char* what) {
    const size_t found = s_.find(end, at_);
    if (found == std::string::npos) fail(std::string("unterminated ") + what);
    advance(found - at_ + std::char_traits<char>::length(end));
  }
  void skip_space() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) advance(1);
  }
  // Whitespace, comments, the declaration and a DOCTYPE between elements.
  void skip_misc() {
    for (;;) {
      skip_space();
      if (starts("<?")) skip_to("?>", "processing instruction");
      else if (starts("<!--")) skip_to("-->", "comment");
      else if (starts("<!DOCTYPE") || starts("<!doctype")) skip_to(">", "DOCTYPE");
      else return;
    }
  }
  std::string name() {
    const size_t begin = at_;
    while (at_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[at_])) || s_[at_] == ':' || s_[at_] == '_' ||
                               s_[at_] == '-' || s_[at_] == '.'))
      advance(1);
    if (at_ == begin) fail("a name was expected");
    return s_.substr(begin, at_ - begin);
  }
  std::string decoded(const std::string& raw) {
    std::string out;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const size_t semi = raw.find(';', i);
      const std::string entity = semi == std::string::npos ? "" : raw.substr(i, semi - i + 1);
      if (entity == "&lt;") out += '<';
      else if (entity == "&gt;") out += '>';
      else if (entity == "&amp;") out += '&';
      else if (entity == "&quot;") out += '"';
      else if (entity == "&apos;") out += '\'';
      else fail("entity '" + entity.substr(0, 12) + "' is not supported");
      i = semi;
    }
    return out;
  }
  XmlElement element() {
    // Each level is a call: a file nesting thousands of elements would exhaust the stack.
    if (++depth_ > kMaxDepth) fail("elements nested deeper than " + std::to_string(kMaxDepth));
    struct Leave {
      int& depth;
      ~Leave() { --depth; }
    } leave{depth_};
    XmlElement e;
    e.line = line_;
    advance(1);  // '<'
    const std::string tag = name();
    e.name = local_name(tag);
    for (;;) {
      skip_space();
      if (starts("/>")) {
        advance(2);
        return e;
      }
      if (starts(">")) {
        advance(1);
        break;
      }
      const std::string key = name();
      skip_space();
      if (!starts("=")) fail("attribute '" + key + "' of <" + tag + "> has no value");
      advance(1);
      skip_space();
      if (at_ >= s_.size() || (s_[at_] != '"' && s_[at_] != '\'')) fail("attribute '" + key + "' needs a quoted value");
      const char quote = s_[at_];
      advance(1);
      const size_t end = s_.find(quote, at_);
      if (end == std::string::npos) fail("unterminated value of attribute '" + key + "'");
      e.attributes.emplace_back(local_name(key), decoded(s_.substr(at_, end - at_)));
      advance(end - at_ + 1);
    }
    for (;;) {
      const size_t next = s_.find('<', at_);
      if (next == std::string::npos) fail("<" + tag + "> is not closed");
      e.text += decoded(s_.substr(at_, next - at_));
      advance(next - at_);
      if (starts("<!--")) skip_to("-->", "comment");
      else if (starts("<![CDATA[")) fail("CDATA sections are not supported");
      else if (starts("<?")) skip_to("?>", "processing instruction");
      else if (starts("</")) {
        advance(2);
        const std::string closing = name();
        if (closing != tag) fail("</" + closing + "> closes <" + tag + ">");
        skip_space();
        if (!starts(">")) fail("'>' expected after </" + closing);
        advance(1);
        return e;
      } else {
        e.children.push_back(element());
      }
    }
  }

  const std::string& s_;
  const std::string& label_;
  static constexpr int kMaxDepth = 64;  // DDAML nests four levels
  size_t at_ = 0;
  int line_ = 1;
  int depth_ = 0;
};

}  // namespace

XmlElement parse_xml(const std::string& text, const std::string& file_label) {
  return Parser(text, file_label).document();
}

}  // namespace ddafit::io
