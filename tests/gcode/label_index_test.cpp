// O-word labels are found by keyword and line, before and after a point, as control flow needs.
#include <doctest/doctest.h>

#include "label_index.hpp"

using ncjoule::detail::LabelIndex;

TEST_CASE("LabelIndex finds the next and the previous line of a label with given keywords") {
  LabelIndex labels;
  labels.add("100", "if", 2);
  labels.add("100", "else", 4);
  labels.add("100", "endif", 6);
  labels.add("100", "if", 8);
  labels.add("100", "endif", 10);
  labels.add("<x>", "sub", 1);
  labels.add("<x>", "sub", 12); // the later definition is the one called
  CHECK(labels.next("100", 2, {"elseif", "else", "endif"}) == 4u);
  CHECK(labels.next("100", 4, {"elseif", "else", "endif"}) == 6u);
  CHECK(labels.next("100", 6, {"endif"}) == 10u);
  CHECK(labels.next("100", 10, {"endif"}) == std::nullopt);
  CHECK(labels.next("200", 0, {"endif"}) == std::nullopt);
  CHECK(labels.previous("100", 10, {"if"}) == 8u);
  CHECK(labels.previous("100", 8, {"if", "else"}) == 4u);
  CHECK(labels.previous("100", 2, {"if"}) == std::nullopt);
  CHECK(labels.last("<x>", "sub") == 12u);
  CHECK(labels.last("<x>", "endsub") == std::nullopt);
}
