#include "xml_tags.hpp"

#include <cstdint>

namespace ncjoule::projects_detail {
namespace {

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == ':' || c == '-' || c == '.' || (static_cast<unsigned char>(c) >= 0x80);
}
bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// A code point as UTF-8.
void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += char(cp);
  } else if (cp < 0x800) {
    out += char(0xc0 | (cp >> 6));
    out += char(0x80 | (cp & 0x3f));
  } else if (cp < 0x10000) {
    out += char(0xe0 | (cp >> 12));
    out += char(0x80 | ((cp >> 6) & 0x3f));
    out += char(0x80 | (cp & 0x3f));
  } else {
    out += char(0xf0 | (cp >> 18));
    out += char(0x80 | ((cp >> 12) & 0x3f));
    out += char(0x80 | ((cp >> 6) & 0x3f));
    out += char(0x80 | (cp & 0x3f));
  }
}

// An attribute value with its entities decoded; std::nullopt at an entity it does not know.
std::optional<std::string> decoded(std::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const std::size_t semi = raw.find(';', i);
    if (semi == std::string_view::npos || semi - i > 12) return std::nullopt;
    const std::string_view entity = raw.substr(i + 1, semi - i - 1);
    if (entity == "amp")
      out += '&';
    else if (entity == "lt")
      out += '<';
    else if (entity == "gt")
      out += '>';
    else if (entity == "quot")
      out += '"';
    else if (entity == "apos")
      out += '\'';
    else if (entity.size() > 1 && entity[0] == '#') {
      const bool hex = entity[1] == 'x' || entity[1] == 'X';
      std::uint32_t cp = 0;
      const std::string_view digits = entity.substr(hex ? 2 : 1);
      if (digits.empty()) return std::nullopt;
      for (char c : digits) {
        int d = c >= '0' && c <= '9'          ? c - '0'
                : hex && c >= 'a' && c <= 'f' ? c - 'a' + 10
                : hex && c >= 'A' && c <= 'F' ? c - 'A' + 10
                                              : -1;
        if (d < 0) return std::nullopt;
        cp = cp * (hex ? 16 : 10) + std::uint32_t(d);
        if (cp > 0x10ffff) return std::nullopt;
      }
      append_utf8(out, cp);
    } else {
      return std::nullopt;
    }
    i = semi;
  }
  return out;
}

} // namespace

const std::string* XmlTag::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

void XmlTags::advance_to(std::size_t at) {
  for (; pos_ < at && pos_ < text_.size(); ++pos_) {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
  }
}

std::optional<XmlTag> XmlTags::fail(std::size_t at, std::string message) {
  advance_to(at);
  error_ = std::move(message);
  error_line_ = line_;
  error_column_ = column_;
  pos_ = text_.size();
  return std::nullopt;
}

std::optional<XmlTag> XmlTags::next() {
  while (true) {
    const std::size_t open = text_.find('<', pos_);
    if (open == std::string_view::npos) {
      advance_to(text_.size());
      return std::nullopt;
    }
    advance_to(open);
    // What is not an element: skipped to its end.
    for (const auto& [start, stop] : {std::pair<std::string_view, std::string_view>{"<!--", "-->"},
                                      {"<![CDATA[", "]]>"},
                                      {"<?", "?>"},
                                      {"<!", ">"}}) {
      if (text_.substr(open, start.size()) != start) continue;
      const std::size_t close = text_.find(stop, open + start.size());
      if (close == std::string_view::npos)
        return fail(open, "'" + std::string(start) + "' is not closed");
      advance_to(close + stop.size());
      goto next_tag;
    }
    {
      XmlTag tag;
      tag.line = line_;
      tag.column = column_;
      std::size_t i = open + 1;
      if (i < text_.size() && text_[i] == '/') {
        tag.closing = true;
        ++i;
      }
      const std::size_t name_begin = i;
      while (i < text_.size() && is_name_char(text_[i]))
        ++i;
      if (i == name_begin) return fail(open, "'<' is not followed by an element name");
      tag.name = std::string(text_.substr(name_begin, i - name_begin));
      while (true) {
        while (i < text_.size() && is_blank(text_[i]))
          ++i;
        if (i >= text_.size()) return fail(open, "tag <" + tag.name + "> is not closed");
        if (text_[i] == '>') {
          advance_to(i + 1);
          return tag;
        }
        if (text_[i] == '/' && i + 1 < text_.size() && text_[i + 1] == '>' && !tag.closing) {
          tag.self_closing = true;
          advance_to(i + 2);
          return tag;
        }
        if (tag.closing) return fail(i, "closing tag </" + tag.name + "> has more than a name");
        const std::size_t key_begin = i;
        while (i < text_.size() && is_name_char(text_[i]))
          ++i;
        if (i == key_begin)
          return fail(i, "unexpected character '" + std::string(1, text_[i]) + "' in tag <" +
                             tag.name + ">");
        std::string key(text_.substr(key_begin, i - key_begin));
        while (i < text_.size() && is_blank(text_[i]))
          ++i;
        if (i >= text_.size() || text_[i] != '=')
          return fail(i, "attribute " + key + " of <" + tag.name + "> has no value");
        ++i;
        while (i < text_.size() && is_blank(text_[i]))
          ++i;
        if (i >= text_.size() || (text_[i] != '"' && text_[i] != '\''))
          return fail(i, "attribute " + key + " of <" + tag.name + "> is not quoted");
        const char quote = text_[i];
        const std::size_t end = text_.find(quote, i + 1);
        if (end == std::string_view::npos)
          return fail(i, "attribute " + key + " of <" + tag.name + "> is not closed");
        auto value = decoded(text_.substr(i + 1, end - i - 1));
        if (!value)
          return fail(i, "attribute " + key + " of <" + tag.name + "> has an unknown entity");
        tag.attributes.emplace_back(std::move(key), std::move(*value));
        i = end + 1;
      }
    }
  next_tag:;
  }
}

} // namespace ncjoule::projects_detail
