// Internal: the style sheet and the script the HTML report inlines.
#pragma once

namespace ncjoule::report_detail {

const char* report_css();
// Tooltips on the time charts; marks <body data-charts-ready="N"> once it has set up N charts,
// which the browser test reads back.
const char* report_script();

} // namespace ncjoule::report_detail
