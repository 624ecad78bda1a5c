// Internal: the tags of an XML document, one at a time, as FreeCAD's Document.xml needs reading:
// element names and attribute values (entities decoded), with the line and column of each tag.
// Text between tags, comments, processing instructions, CDATA and DOCTYPE are skipped. Not a
// validating parser: it reads what is well formed and says where it stops when it is not.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ncjoule::projects_detail {

struct XmlTag {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  bool closing = false;      // </name>
  bool self_closing = false; // <name ... />
  int line = 0, column = 0;  // 1-based, of its '<'
  // The attribute's value; nullptr when the tag has none of that name.
  const std::string* attribute(std::string_view key) const;
};

class XmlTags {
public:
  explicit XmlTags(std::string_view text) : text_(text) {}
  // The next tag; std::nullopt at the end, or (with error() set) where the text is not XML.
  std::optional<XmlTag> next();
  const std::string& error() const { return error_; }
  int error_line() const { return error_line_; }
  int error_column() const { return error_column_; }

private:
  std::optional<XmlTag> fail(std::size_t at, std::string message);
  void advance_to(std::size_t at); // keeps line_ and column_ in step with pos_
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
  std::string error_;
  int error_line_ = 0, error_column_ = 0;
};

} // namespace ncjoule::projects_detail
