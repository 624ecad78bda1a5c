// A FreeCAD document's Path Job and its Stock (projects.hpp says what is read and what is not).
//
// Document.xml lists every object under <ObjectData>, each with its properties:
//   <Object name="Stock"> <Properties> <Property name="Length" type="App::PropertyLength">
//   <Float value="70.0"/> </Property> ... <Property name="Placement"> <PropertyPlacement Px=".."
//   Py=".." Pz=".." Q0=".." Q1=".." Q2=".." Q3=".."/> ... <Property name="Proxy"> <Python
//   module="PathScripts.PathStock" class="StockCreateBox"/> ...
// A Job is the object whose Proxy's class is ObjectJob; its Stock property links the stock
// object by name. Lengths are in mm, FreeCAD's internal unit.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "brep_bounds.hpp"
#include "ncjoule/projects.hpp"
#include "ncjoule/text.hpp"
#include "ncjoule/text_file.hpp"
#include "xml_tags.hpp"
#include "zip_archive.hpp"

namespace ncjoule {
namespace {

using projects_detail::XmlTag;
using projects_detail::XmlTags;

// The largest FreeCAD document read, and the largest Document.xml or shape inflated from it.
constexpr std::size_t kMaxDocumentBytes = std::size_t(256) << 20;
constexpr std::size_t kMaxMemberBytes = std::size_t(64) << 20;

struct Property {
  std::string type;
  XmlTag value; // the first element inside <Property>: <Float value=..>, <Link value=..>, ...
  int line = 0, column = 0;
};
struct Object {
  std::string name;
  std::map<std::string, Property> properties;
  const Property* property(const std::string& key) const {
    auto it = properties.find(key);
    return it == properties.end() ? nullptr : &it->second;
  }
  // The value="..." of a property's element (Float, Link, String, Bool, Integer).
  const std::string* value(const std::string& key) const {
    const Property* p = property(key);
    return p ? p->value.attribute("value") : nullptr;
  }
  // The class of its Python proxy ("ObjectJob", "StockCreateBox", ...); empty without one.
  std::string proxy_class() const {
    const Property* p = property("Proxy");
    const std::string* c = p ? p->value.attribute("class") : nullptr;
    return c ? *c : std::string();
  }
};

struct Document {
  std::string label; // the document's Label (what %d in an output file name stands for)
  std::vector<Object> objects;
  const Object* find(const std::string& name) const {
    for (const Object& o : objects)
      if (o.name == name) return &o;
    return nullptr;
  }
};

// Document.xml's objects; std::nullopt with `error`, `line`, `column` where it is not XML.
std::optional<Document> read_objects(std::string_view xml, std::string& error, int& line,
                                     int& column) {
  Document doc;
  XmlTags tags(xml);
  int depth = 0;                // element depth
  int object_data_depth = -1;   // depth of <ObjectData>
  int document_props = -1;      // depth of the document's own <Properties>
  Object* object = nullptr;     // inside <ObjectData><Object>
  Property* property = nullptr; // inside <Property>, before its first element
  std::string property_name;
  bool in_document_label = false;
  while (auto tag = tags.next()) {
    if (tag->closing) {
      --depth;
      if (tag->name == "ObjectData" && depth == object_data_depth) object_data_depth = -1;
      if (tag->name == "Object" && object_data_depth >= 0 && depth == object_data_depth + 1)
        object = nullptr;
      if (tag->name == "Property") property = nullptr, in_document_label = false;
      if (tag->name == "Properties" && depth == document_props) document_props = -1;
      continue;
    }
    const int here = depth;
    if (!tag->self_closing) ++depth;
    if (tag->name == "ObjectData") {
      object_data_depth = here;
    } else if (tag->name == "Properties" && here == 1 && object_data_depth < 0) {
      document_props = here;
    } else if (tag->name == "Object" && object_data_depth >= 0 && here == object_data_depth + 1) {
      doc.objects.push_back({});
      object = &doc.objects.back();
      if (const std::string* name = tag->attribute("name")) object->name = *name;
    } else if (tag->name == "Property") {
      const std::string* name = tag->attribute("name");
      if (object && name) {
        Property& p = object->properties[*name];
        if (const std::string* type = tag->attribute("type")) p.type = *type;
        p.line = tag->line, p.column = tag->column;
        property = tag->self_closing ? nullptr : &p;
      } else if (document_props >= 0 && name && *name == "Label") {
        in_document_label = true;
      }
    } else if (property) {
      property->value = std::move(*tag);
      property = nullptr;
    } else if (in_document_label) {
      if (const std::string* v = tag->attribute("value")) doc.label = *v;
      in_document_label = false;
    }
  }
  if (!tags.error().empty()) {
    error = tags.error(), line = tags.error_line(), column = tags.error_column();
    return std::nullopt;
  }
  return doc;
}

std::optional<double> number(const std::string* text) {
  if (!text) return std::nullopt;
  const auto v = parse_number(*text);
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return v;
}

// The file name a Job's PostProcessorOutputFile gives (its %d, %j and %s filled in as FreeCAD's
// post command fills them; the folder left out); empty when it gives none.
std::string output_file_name(const Document& doc, const Object& job) {
  const std::string* file = job.value("PostProcessorOutputFile");
  if (!file || file->empty()) return {};
  std::string name = *file;
  const std::size_t slash = name.find_last_of("/\\");
  if (slash != std::string::npos) name = name.substr(slash + 1);
  const std::string* job_label = job.value("Label");
  auto replace = [&](std::string_view key, const std::string& with) {
    for (std::size_t at; (at = name.find(key)) != std::string::npos;)
      name.replace(at, key.size(), with);
  };
  replace("%d", doc.label);
  replace("%j", job_label ? *job_label : job.name);
  replace("%s", "");
  return name;
}

// The Placement's translation, when it turns nothing (an identity rotation); std::nullopt
// with `why` otherwise.
std::optional<std::array<double, 3>> translation(const Object& o, std::string& why) {
  const Property* p = o.property("Placement");
  if (!p) return std::array<double, 3>{0, 0, 0};
  const XmlTag& v = p->value;
  const auto x = number(v.attribute("Px")), y = number(v.attribute("Py")),
             z = number(v.attribute("Pz"));
  if (!x || !y || !z) return why = "its Placement has no position", std::nullopt;
  // The quaternion (Q0, Q1, Q2, Q3) = (x, y, z, w); missing parts are no rotation.
  const double q[3] = {number(v.attribute("Q0")).value_or(0), number(v.attribute("Q1")).value_or(0),
                       number(v.attribute("Q2")).value_or(0)};
  if (std::abs(q[0]) > 1e-9 || std::abs(q[1]) > 1e-9 || std::abs(q[2]) > 1e-9)
    return why = "its Placement turns it (ncjoule takes a stock box along the axes)", std::nullopt;
  return std::array<double, 3>{*x, *y, *z};
}

} // namespace

bool reads_freecad_documents() {
  return projects_detail::zip_inflates();
}

std::optional<ProjectFile> parse_freecad_document(std::string_view bytes, const std::string& path,
                                                  const std::string& program,
                                                  std::vector<Diagnostic>& diagnostics,
                                                  bool posting_only) {
  const std::string name = std::filesystem::path(path).filename().string();
  auto warn = [&](std::string message, std::string file = {}, int line = 0, int column = 0) {
    diagnostics.push_back({Severity::Warning, file.empty() ? path : file, line, column,
                           "FreeCAD document not read: " + std::move(message)});
    return std::nullopt;
  };
  std::string error;
  const auto xml = projects_detail::zip_member(bytes, "Document.xml", kMaxMemberBytes, error);
  if (!xml) return warn(error);
  const std::string xml_file = path + "/Document.xml"; // where its diagnostics point
  int line = 0, column = 0;
  const auto doc = read_objects(*xml, error, line, column);
  if (!doc) return warn(error, xml_file, line, column);

  // The Job that posts the program.
  const std::string program_name = std::filesystem::path(program).filename().string();
  std::vector<const Object*> jobs, posting;
  for (const Object& o : doc->objects)
    if (o.proxy_class() == "ObjectJob") {
      jobs.push_back(&o);
      const std::string out = output_file_name(*doc, o);
      if (!out.empty() && out == program_name) posting.push_back(&o);
    }
  if (posting_only && posting.empty()) return std::nullopt;
  if (jobs.empty()) return warn("it holds no Path Job");
  const Object* job = posting.size() == 1                   ? posting.front()
                      : jobs.size() == 1 && posting.empty() ? jobs.front()
                                                            : nullptr;
  if (!job)
    return warn("it holds " + std::to_string(jobs.size()) + " Jobs and " +
                (posting.empty() ? std::string("none") : std::to_string(posting.size())) +
                " whose PostProcessorOutputFile names " + program_name +
                ": give the stock with --stock or a job file");
  const std::string* job_label = job->value("Label");
  const std::string job_name = job_label && !job_label->empty() ? *job_label : job->name;

  ProjectFile project;
  project.path = path;
  const std::string* stock_link = job->value("Stock");
  const Object* stock = stock_link && !stock_link->empty() ? doc->find(*stock_link) : nullptr;
  if (!stock) {
    diagnostics.push_back({Severity::Warning, path, 0, 0,
                           "FreeCAD job '" + job_name + "' in " + name + " has no stock"});
    return project;
  }
  // Its kind: the StockType property newer FreeCADs write, else the proxy's class, else the
  // properties it has (as FreeCAD's own PathStock.StockType.FromStock decides).
  std::string kind;
  if (const std::string* t = stock->value("StockType")) kind = *t;
  const std::string proxy = stock->proxy_class();
  if (kind.empty())
    kind = proxy == "StockCreateBox"                                  ? "CreateBox"
           : proxy == "StockFromBase"                                 ? "FromBase"
           : proxy == "StockCreateCylinder"                           ? "CreateCylinder"
           : stock->property("ExtXneg") && stock->property("ExtZpos") ? "FromBase"
           : stock->property("Length") && stock->property("Width")    ? "CreateBox"
           : stock->property("Radius") && stock->property("Height")   ? "CreateCylinder"
                                                                      : "";
  const std::string what =
      "FreeCAD job " + name + " ('" + job_name + "', Stock: " +
      (kind == "FromBase" ? std::string("ExtendedBoundBox")
       : kind.empty()     ? "a solid" + std::string(proxy.empty() ? "" : " (" + proxy + ")")
                          : kind) +
      ")";
  auto unread = [&](const std::string& why) {
    diagnostics.push_back({Severity::Warning, xml_file,
                           stock->property("Placement") ? stock->property("Placement")->line : 0, 0,
                           what + ": " + why + "; the next source of the stock is used"});
    return project;
  };
  std::string why;
  const auto at = translation(*stock, why);
  if (!at) return unread(why);
  Box3 box;
  if (kind == "CreateBox") {
    const auto l = number(stock->value("Length")), w = number(stock->value("Width")),
               h = number(stock->value("Height"));
    if (!l || !w || !h) return unread("its Length, Width or Height is missing");
    box = Box3{(*at)[0], (*at)[1], (*at)[2], (*at)[0] + *l, (*at)[1] + *w, (*at)[2] + *h};
  } else if (kind == "FromBase") {
    // The stock's shape is the model's bounding box with the allowances: its vertices, moved by
    // the shape's location (which is the Placement, as FreeCAD saves a shape).
    const Property* shape = stock->property("Shape");
    const std::string* file = shape ? shape->value.attribute("file") : nullptr;
    if (!file || file->empty()) return unread("its shape is not saved in the document");
    const auto brep = projects_detail::zip_member(bytes, *file, kMaxMemberBytes, error);
    if (!brep) return unread("its shape " + error);
    const auto bounds = projects_detail::brep_vertex_bounds(*brep, why);
    if (!bounds) return unread("its shape " + *file + ": " + why);
    box = *bounds;
  } else if (kind == "CreateCylinder") {
    const auto r = number(stock->value("Radius")), h = number(stock->value("Height"));
    std::ostringstream size;
    if (r && h) size << " (radius " << *r << " mm, height " << *h << " mm)";
    return unread("a cylinder stock" + size.str() +
                  " is not modelled (ncjoule takes box and STL stocks: export it as an STL and "
                  "give it with --stock)");
  } else {
    return unread("a stock of this kind is not read (export it as an STL and give it with "
                  "--stock)");
  }
  if (!(box.xmax > box.xmin && box.ymax > box.ymin && box.zmax > box.zmin))
    return unread("its box has no volume");
  StockSpec spec;
  spec.kind = StockSpec::Kind::Box;
  spec.box = box;
  spec.box_units.fill(LengthUnit::Mm);
  spec.from = "freecad-job";
  spec.origin = what;
  project.stock = spec;
  return project;
}

std::optional<ProjectFile> read_freecad_document(const std::string& path,
                                                 const std::string& program,
                                                 std::vector<Diagnostic>& diagnostics,
                                                 bool posting_only) {
  std::vector<Diagnostic> problems;
  const auto bytes = read_text_file(path, "a FreeCAD document", problems, kMaxDocumentBytes);
  if (!bytes) {
    for (Diagnostic& d : problems) {
      d.severity = Severity::Warning;
      d.message = "FreeCAD document not read: " + d.message;
      diagnostics.push_back(std::move(d));
    }
    return std::nullopt;
  }
  return parse_freecad_document(*bytes, path, program, diagnostics, posting_only);
}

} // namespace ncjoule
