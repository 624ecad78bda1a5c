// G and M codes as numbers (see codes.hpp).
#include "codes.hpp"

#include <algorithm>
#include <cstdio>

namespace ncjoule::detail {

int g_group(int code) {
  switch (code) {
  case 0:
  case 10:
  case 20:
  case 30:
  case 330:
  case 331:
  case 382:
  case 383:
  case 384:
  case 385:
  case 730:
  case 740:
  case 760:
  case 800:
  case 810:
  case 820:
  case 830:
  case 840:
  case 850:
  case 860:
  case 870:
  case 880:
  case 890:
    return 1;
  case 170:
  case 180:
  case 190:
    return 2;
  case 900:
  case 910:
    return 3;
  case 901:
  case 911:
    return 4;
  case 930:
  case 940:
  case 950:
    return 5;
  case 200:
  case 210:
    return 6;
  case 400:
  case 410:
  case 411:
  case 420:
  case 421:
  case 412:
  case 422:
    return 7;
  case 430:
  case 431:
  case 432:
  case 490:
    return 8;
  case 980:
  case 990:
    return 10;
  case 540:
  case 550:
  case 560:
  case 570:
  case 580:
  case 590:
  case 591:
  case 592:
  case 593:
    return 12;
  case 610:
  case 611:
  case 640:
    return 13;
  case 40:
  case 100:
  case 280:
  case 281:
  case 300:
  case 301:
  case 530:
  case 920:
  case 921:
  case 922:
  case 923:
    return 0;
  default:
    return -1;
  }
}

std::string g_name(int code) {
  std::string s = "G" + std::to_string(code / 10);
  if (code % 10) s += "." + std::to_string(code % 10);
  return s;
}

// Codes that change only how a controller blends or smooths the path: kept as planner hints.
// - Haas G187 P1/P2/P3 E<tol> (Haas Mill Operator's Manual, "G187 Accuracy Control"): rough,
//   medium or finish smoothing, E the corner rounding tolerance.
// - Haas G103 P<n> ("G103 Limit Block Lookahead"): at most n blocks of look-ahead, P0 none.
// - Fanuc G05.1 Q1/Q0 (AI contour control on/off), G08 P1/P0 (advanced preview control), G05
//   P10000 (high-speed machining mode). G5/G5.1 are splines in LinuxCNC, hence the dialect test.
// - Sinumerik G641/G642/G643/G644/G645: continuous path with rounding.
bool is_planner_hint_g(int code, const Dialect& dialect) {
  if (code == 1870 || code == 1030 || code == 80 || code == 81) return true;
  if (dialect.sinumerik_words && code >= 6410 && code <= 6450) return true;
  const bool linuxcnc = dialect.o_word_subroutines;
  return !linuxcnc && (code == 51 || code == 50);
}

std::string number_text(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  return buf;
}

} // namespace ncjoule::detail
