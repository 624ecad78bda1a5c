// FreeCAD documents saved by real FreeCAD 0.20 (data/, remade by
// scripts/make_freecad_stock_documents.py): the Job's stock read back, and damaged documents
// said to be so, never read as a stock.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "brep_bounds.hpp"
#include "ncjoule/projects.hpp"
#include "xml_tags.hpp"
#include "zip_archive.hpp"

using namespace ncjoule;

namespace {

std::string data(const std::string& name) {
  return std::string(NCJOULE_PROJECTS_DATA) + "/" + name;
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void put16(std::string& s, std::uint32_t v) {
  s += char(v & 0xff);
  s += char((v >> 8) & 0xff);
}
void put32(std::string& s, std::uint32_t v) {
  put16(s, v & 0xffff);
  put16(s, v >> 16);
}

// A zip archive of stored (uncompressed) members, as the format lays it out.
std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& members) {
  std::string out, directory;
  for (const auto& [name, body] : members) {
    const std::uint32_t local = std::uint32_t(out.size());
    put32(out, 0x04034b50);
    put16(out, 20), put16(out, 0), put16(out, 0), put16(out, 0), put16(out, 0);
    put32(out, 0), put32(out, std::uint32_t(body.size())), put32(out, std::uint32_t(body.size()));
    put16(out, std::uint32_t(name.size())), put16(out, 0);
    out += name + body;
    put32(directory, 0x02014b50);
    put16(directory, 20), put16(directory, 20), put16(directory, 0), put16(directory, 0);
    put16(directory, 0), put16(directory, 0);
    put32(directory, 0), put32(directory, std::uint32_t(body.size()));
    put32(directory, std::uint32_t(body.size()));
    put16(directory, std::uint32_t(name.size()));
    put16(directory, 0), put16(directory, 0), put16(directory, 0), put16(directory, 0);
    put32(directory, 0), put32(directory, local);
    directory += name;
  }
  const std::uint32_t at = std::uint32_t(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0), put16(out, 0);
  put16(out, std::uint32_t(members.size())), put16(out, std::uint32_t(members.size()));
  put32(out, std::uint32_t(directory.size())), put32(out, at);
  put16(out, 0);
  return out;
}

bool mentions(const std::vector<Diagnostic>& d, const std::string& text) {
  for (const Diagnostic& x : d)
    if (x.message.find(text) != std::string::npos) return true;
  return false;
}

} // namespace

TEST_CASE("a FreeCAD Job's CreateBox stock: Length, Width, Height at its Placement") {
  REQUIRE(reads_freecad_documents());
  std::vector<Diagnostic> d;
  const auto p = read_freecad_document(data("box.FCStd"), "out/box.ngc", d);
  REQUIRE(p);
  CHECK(d.empty());
  REQUIRE(p->stock);
  const Box3& b = p->stock->box;
  CHECK(b.xmin == -5);
  CHECK(b.ymin == -5);
  CHECK(b.zmin == -11);
  CHECK(b.xmax == 65);
  CHECK(b.ymax == 45);
  CHECK(b.zmax == 1);
  CHECK(p->stock->from == "freecad-job");
  CHECK(p->stock->origin == "FreeCAD job box.FCStd ('Job', Stock: CreateBox)");
  CHECK(p->stock->box_units[0] == LengthUnit::Mm); // FreeCAD's mm, whatever the program's units
}

TEST_CASE("a FreeCAD Job's ExtendedBoundBox stock: the model's box with the allowances") {
  std::vector<Diagnostic> d;
  const auto p = read_freecad_document(data("extended.FCStd"), "extended.nc", d);
  REQUIRE(p);
  REQUIRE(p->stock);
  const Box3& b = p->stock->box;
  // The 60 x 40 x 10 body with its top at Z0, 1 mm around (FreeCAD's default allowances).
  CHECK(b.xmin == doctest::Approx(-1));
  CHECK(b.ymin == doctest::Approx(-1));
  CHECK(b.zmin == doctest::Approx(-11));
  CHECK(b.xmax == doctest::Approx(61));
  CHECK(b.ymax == doctest::Approx(41));
  CHECK(b.zmax == doctest::Approx(1));
  CHECK(p->stock->origin.find("ExtendedBoundBox") != std::string::npos);
}

TEST_CASE("a FreeCAD cylinder stock is named, not taken") {
  std::vector<Diagnostic> d;
  const auto p = read_freecad_document(data("cylinder.FCStd"), "cylinder.nc", d);
  REQUIRE(p);
  CHECK_FALSE(p->stock);
  REQUIRE(d.size() == 1);
  CHECK(d[0].severity == Severity::Warning);
  CHECK(d[0].message.find("cylinder stock (radius 40 mm, height 12 mm)") != std::string::npos);
  CHECK(d[0].file.find("cylinder.FCStd/Document.xml") != std::string::npos);
  CHECK(d[0].line > 0);
}

TEST_CASE("of two FreeCAD Jobs, the one whose output file is the program") {
  std::vector<Diagnostic> d;
  // "%D/%d-top.nc": the document's label is "twojobs".
  auto top = read_freecad_document(data("twojobs.FCStd"), "x/twojobs-top.nc", d);
  REQUIRE(top);
  REQUIRE(top->stock);
  CHECK(top->stock->box.xmax == 65);
  CHECK(top->stock->origin.find("'Top'") != std::string::npos);
  auto bottom = read_freecad_document(data("twojobs.FCStd"), "bottom.nc", d);
  REQUIRE(bottom);
  REQUIRE(bottom->stock);
  CHECK(bottom->stock->box.xmin == -10);
  CHECK(bottom->stock->box.zmax == 1);
  CHECK(d.empty());
  CHECK_FALSE(read_freecad_document(data("twojobs.FCStd"), "other.nc", d));
  REQUIRE(d.size() == 1);
  CHECK(d[0].message.find("2 Jobs and none") != std::string::npos);
  // Asked only for a Job that posts the program, a document with one Job says nothing.
  d.clear();
  CHECK_FALSE(read_freecad_document(data("box.FCStd"), "other.nc", d, true));
  CHECK(d.empty());
}

TEST_CASE("a damaged FreeCAD document is a warning, never a crash or a stock") {
  const std::string good = bytes_of(data("box.FCStd"));
  REQUIRE(good.size() > 1000);
  std::vector<Diagnostic> d;
  // Not a zip; cut short anywhere; a byte flipped in the deflated data.
  CHECK_FALSE(parse_freecad_document("G0 X1\n", "p.FCStd", "p.nc", d));
  CHECK(mentions(d, "not a zip archive"));
  for (std::size_t keep :
       {std::size_t(0), std::size_t(30), good.size() / 2, good.size() - 23, good.size() - 1}) {
    CAPTURE(keep);
    d.clear();
    CHECK_FALSE(parse_freecad_document(good.substr(0, keep), "p.FCStd", "p.nc", d));
    REQUIRE(d.size() == 1);
    CHECK(d[0].severity == Severity::Warning);
  }
  for (std::size_t at = 40; at < 400; at += 37) {
    std::string flipped = good;
    flipped[at] = char(flipped[at] ^ 0x5a);
    d.clear();
    parse_freecad_document(flipped, "p.FCStd", "p.nc", d); // whatever it reads, it does not crash
  }
  // A zip without Document.xml; a Document.xml that is not XML: where it stops.
  d.clear();
  CHECK_FALSE(parse_freecad_document(stored_zip({{"a.txt", "x"}}), "p.FCStd", "p.nc", d));
  CHECK(mentions(d, "holds no Document.xml"));
  d.clear();
  CHECK_FALSE(parse_freecad_document(
      stored_zip({{"Document.xml", "<?xml version='1.0'?>\n<Document>\n  <ObjectData Count=1>\n"}}),
      "p.FCStd", "p.nc", d));
  REQUIRE(d.size() == 1);
  CHECK(d[0].file == "p.FCStd/Document.xml");
  CHECK(d[0].line == 3);
  CHECK(d[0].column == 21);
  CHECK(d[0].message.find("not quoted") != std::string::npos);
  // XML that holds no Job.
  d.clear();
  CHECK_FALSE(parse_freecad_document(
      stored_zip({{"Document.xml", "<Document><ObjectData/></Document>"}}), "p.FCStd", "p.nc", d));
  CHECK(mentions(d, "no Path Job"));
  // A Job whose stock is a box with a turned Placement: named, not read.
  const std::string turned = R"(<Document><ObjectData>
<Object name="Job"><Properties>
 <Property name="Proxy" type="App::PropertyPythonObject"><Python value="" class="ObjectJob"/></Property>
 <Property name="Stock" type="App::PropertyLink"><Link value="Stock"/></Property>
</Properties></Object>
<Object name="Stock"><Properties>
 <Property name="Proxy" type="App::PropertyPythonObject"><Python value="" class="StockCreateBox"/></Property>
 <Property name="Length" type="App::PropertyLength"><Float value="10"/></Property>
 <Property name="Width" type="App::PropertyLength"><Float value="10"/></Property>
 <Property name="Height" type="App::PropertyLength"><Float value="10"/></Property>
 <Property name="Placement" type="App::PropertyPlacement"><PropertyPlacement Px="0" Py="0" Pz="0" Q0="0" Q1="0" Q2="0.38268343" Q3="0.92387953"/></Property>
</Properties></Object></ObjectData></Document>)";
  d.clear();
  const auto p =
      parse_freecad_document(stored_zip({{"Document.xml", turned}}), "p.FCStd", "p.nc", d);
  REQUIRE(p);
  CHECK_FALSE(p->stock);
  CHECK(mentions(d, "turns it"));
}

TEST_CASE("XML tags: names, attributes with entities, and where malformed XML stops") {
  using projects_detail::XmlTags;
  XmlTags tags("<?xml version='1.0'?><!-- a > b --><a x=\"1 &amp; &lt;2&gt; &#65;&#x42;\">"
               "text<b y='q'/></a>");
  auto a = tags.next();
  REQUIRE(a);
  CHECK(a->name == "a");
  REQUIRE(a->attribute("x"));
  CHECK(*a->attribute("x") == "1 & <2> AB");
  auto b = tags.next();
  REQUIRE(b);
  CHECK(b->self_closing);
  CHECK(*b->attribute("y") == "q");
  auto end = tags.next();
  REQUIRE(end);
  CHECK(end->closing);
  CHECK_FALSE(tags.next());
  CHECK(tags.error().empty());
  for (const char* bad : {"<a x=\"1", "<a x=1>", "<a x>", "< a>", "<a x=\"&bogus;\">", "<!-- open",
                          "<a", "</a x=\"1\">"}) {
    CAPTURE(std::string(bad));
    XmlTags t(bad);
    CHECK_FALSE(t.next());
    CHECK_FALSE(t.error().empty());
    CHECK(t.error_line() == 1);
  }
}

TEST_CASE("BREP vertex bounds: the shape's one location moves them, a turned one is refused") {
  using projects_detail::brep_vertex_bounds;
  const std::string head = "\nCASCADE Topology V1, (c) Matra-Datavision\nLocations 1\n1\n";
  const std::string rows = "1 0 0 5\n0 1 0 -2\n0 0 1 -10\n";
  const std::string vertices = "TShapes 2\nVe\n1e-07\n-1 -1 -1\n0 0\n\n0101101\n*\n"
                               "Ve\n1e-07\n61 41 11\n0 0\n\n0101101\n*\n";
  std::string why;
  const auto box = brep_vertex_bounds(head + rows + vertices, why);
  REQUIRE(box);
  CHECK(box->xmin == 4);
  CHECK(box->ymax == 39);
  CHECK(box->zmin == -11);
  CHECK(box->zmax == 1);
  CHECK_FALSE(brep_vertex_bounds(head + "0 -1 0 5\n1 0 0 -2\n0 0 1 -10\n" + vertices, why));
  CHECK(why.find("turns") != std::string::npos);
  CHECK_FALSE(brep_vertex_bounds("solid cube\nendsolid\n", why));
  CHECK_FALSE(brep_vertex_bounds(head + rows + "TShapes 0\n", why));
  CHECK(why == "has no vertex");
  CHECK_FALSE(brep_vertex_bounds(head + rows + "Ve\n1e-07\n1 two 3\n", why));
}

TEST_CASE("the project beside a program: a CAMotics project naming it, else its FreeCAD document") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "ncjoule-projects-beside-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
  };
  write("box.ngc", "G0 X0\n");
  std::vector<Diagnostic> d;
  CHECK_FALSE(project_beside((dir / "box.ngc").string(), d));
  // Its FreeCAD document, with a damaged CAMotics project beside it: a warning, then the next.
  fs::copy_file(data("box.FCStd"), dir / "box.FCStd");
  write("broken.camotics", "{\"files\": [\"box.ngc\"");
  auto p = project_beside((dir / "box.ngc").string(), d);
  REQUIRE(p);
  REQUIRE(p->stock);
  CHECK(p->stock->from == "freecad-job");
  REQUIRE(d.size() == 1);
  CHECK(d[0].severity == Severity::Warning);
  CHECK(d[0].file.find("broken.camotics") != std::string::npos);
  // A CAMotics project that names the program comes first; the other is noted.
  write("job.camotics", R"({"workpiece": {"automatic": false, "bounds": {"min": [0,0,-5],
      "max": [10,10,0]}}, "files": ["box.ngc"]})");
  d.clear();
  p = project_beside((dir / "box.ngc").string(), d);
  REQUIRE(p);
  CHECK(p->stock->from == "camotics");
  CHECK(mentions(d, "also gives a stock"));
  // Another program in the folder has none of them (the document is box's, its Job posts no
  // other), and standard input has none.
  write("other.ngc", "G0 X0\n");
  d.clear();
  CHECK_FALSE(project_beside((dir / "other.ngc").string(), d));
  CHECK_FALSE(project_beside("-", d));
  fs::remove_all(dir);
}
