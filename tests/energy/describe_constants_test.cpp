// The result header names the constants used: for every sample profile, the model description
// holds the value of every constant the profile's model evaluates (per-axis KA/KB included), and
// the Combined description names the Zhou cutting term next to them.
#include <doctest/doctest.h>

#include <cstdio>
#include <string>

#include "ncjoule/energy.hpp"
#include "ncjoule/profile.hpp"

using namespace ncjoule;

namespace {

std::string as_printed(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

} // namespace

TEST_CASE("the model description lists every constant of the sample profiles' models") {
  for (const char* file :
       {"generic-3axis.toml", "haas-vf0-pavanaskar2014.toml", "zhou2017-anziani2025.toml"}) {
    CAPTURE(file);
    const MachineProfile m =
        load_profile(std::string(NCJOULE_SOURCE_DIR) + "/samples/machines/" + file);
    const std::string text = describe_power_constants(m.power);
    MESSAGE(std::string(file) << ": " << text);
    std::string name(model_name(m.power.model));
    name[0] = static_cast<char>(name[0] - 'a' + 'A');
    CHECK(text.rfind(name, 0) == 0); // "Combined ...", "Pavanaskar ...", "Zhou ..."
    for (PowerParameter p : model_parameters(m.power.model)) {
      CAPTURE(parameter_info(p).key);
      CHECK(text.find(as_printed(get_parameter(m.power, p))) != std::string::npos);
    }
  }
}

TEST_CASE("the model description shows per-axis values in X/Y/Z order") {
  PowerConstants k;
  k.model = PowerModel::Combined;
  k.pavanaskar.move_ka_w = {11, 22, 33};
  k.pavanaskar.move_kb_w_per_mm_s = {0.25, 0.5, 0.75};
  k.zhou.c3 = 7.5e-7;
  k.zhou.c4 = 1.2;
  const std::string text = describe_power_constants(k);
  CHECK(text.find("move X/Y/Z KA 11/22/33 W KB 0.25/0.5/0.75 W/(mm/s)") != std::string::npos);
  CHECK(text.find("cutting 7.5e-07*n^1.2*MRR kW") != std::string::npos);
  k.model = PowerModel::Pavanaskar;
  k.pavanaskar.cut_ka_w = {1, 2, 3};
  k.pavanaskar.cut_kb_w_per_mm3_s = {4, 5, 6};
  CHECK(describe_power_constants(k).find("cut X/Y/Z KA 1/2/3 W KB 4/5/6 W/(mm^3/s)") !=
        std::string::npos);
}
