// The report's inline style sheet and script. No external URL anywhere: the page must open on a
// shop-floor PC without network.
#include "html_assets.hpp"

namespace ncjoule::report_detail {

const char* report_css() {
  return R"CSS(
:root{--ink:#1f2933;--muted:#64748b;--line:#e2e8f0;--bg:#f4f6f9;--card:#fff;--accent:#1c7ed6}
*{box-sizing:border-box}
body{margin:0;background:var(--bg);color:var(--ink);
 font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
header.top{background:#1e293b;color:#f8fafc;padding:22px 36px 18px}
header.top h1{margin:0;font-size:22px;font-weight:600;letter-spacing:.2px}
header.top .sub{margin-top:4px;color:#cbd5e1;font-size:13px}
header.top .brand{float:right;font-size:12px;color:#94a3b8;margin-top:6px}
main{max-width:1180px;margin:0 auto;padding:20px 28px 40px}
section{background:var(--card);border:1px solid var(--line);border-radius:10px;
 padding:18px 22px 8px;margin:0 0 22px;box-shadow:0 1px 2px rgba(15,23,42,.04)}
section h2{margin:0 0 2px;font-size:18px;font-weight:600}
section .path{color:var(--muted);font-size:12px;margin-bottom:14px;word-break:break-all}
h3{font-size:14px;margin:18px 0 6px;color:#334155;font-weight:600}
.kpis{display:grid;grid-template-columns:repeat(auto-fit,minmax(150px,1fr));gap:10px;margin:6px 0 10px}
.kpi{border:1px solid var(--line);border-radius:8px;padding:10px 12px;background:#fbfcfe}
.kpi .label{font-size:11px;text-transform:uppercase;letter-spacing:.6px;color:var(--muted)}
.kpi .value{font-size:20px;font-weight:600;margin-top:2px;font-variant-numeric:tabular-nums}
.kpi .extra{font-size:12px;color:var(--muted);font-variant-numeric:tabular-nums}
.kpi .guessed{background:#fff3cd;color:#7a5b00;border-radius:4px;padding:0 4px;text-transform:none;letter-spacing:0}
figure.chart{margin:10px 0 14px;position:relative}
figure.chart figcaption{font-weight:600;font-size:14px;color:#334155;margin-bottom:4px}
figure.chart svg{width:100%;height:auto;display:block}
.legend{display:flex;flex-wrap:wrap;gap:4px 16px;font-size:12px;color:#475569;margin:2px 0 4px}
.legend i{display:inline-block;width:11px;height:11px;border-radius:2px;margin-right:5px;vertical-align:-1px}
svg text{font-family:inherit;font-size:12px;fill:#475569}
svg .grid line{stroke:#eef2f6;stroke-width:1}
svg .ylabel{text-anchor:end;dominant-baseline:middle}
svg .xlabel{text-anchor:middle}
svg .axis-title{font-size:12px;fill:#64748b}
svg .axis-title.end{text-anchor:end}
svg .frame{fill:none;stroke:#cbd5e1;stroke-width:1}
svg path.line{fill:none;stroke-width:1.4;stroke-linejoin:round}
svg path.line.faint{stroke-opacity:.35;stroke-width:1}
.measured table.runs td.name{white-space:normal}
svg.toolpath-view path.feed{fill:none;stroke-width:1.6;stroke-linecap:round}
svg.toolpath-view path.rapid{fill:none;stroke:#94a3b8;stroke-width:.7;stroke-dasharray:4 3}
svg.toolpath-view path:hover{stroke-width:4}
.legend.scale{gap:0;align-items:center}
.legend.scale i{width:22px;margin:0;border-radius:0}
.legend.scale span{margin:0 8px}
svg.timeline-view rect.op{stroke:#fff;stroke-width:1}
svg.timeline-view rect.op:hover{opacity:.8}
svg.timeline-view text.op-label{font-size:12px;fill:#fff}
svg.timeline-view text.time{font-size:11px;fill:#64748b}
svg.timeline-view text.time.end{text-anchor:end}
svg path.area{fill-opacity:.14;stroke:none}
svg .markers line{stroke:#94a3b8;stroke-dasharray:4 3;stroke-width:1}
svg .markers text{font-size:11px;fill:#334155}
svg .cursor{stroke:#0f172a;stroke-width:1;stroke-opacity:.5}
svg .track{fill:#f1f5f9}
svg .bar-label{text-anchor:end;dominant-baseline:middle;fill:#1f2933}
svg .bar-value{dominant-baseline:middle;font-variant-numeric:tabular-nums;fill:#1f2933}
.tooltip{position:absolute;pointer-events:none;background:#0f172a;color:#f8fafc;font-size:12px;
 padding:6px 9px;border-radius:6px;white-space:nowrap;box-shadow:0 2px 6px rgba(0,0,0,.2)}
.tooltip i{display:inline-block;width:9px;height:9px;border-radius:2px;margin-right:5px}
table{border-collapse:collapse;width:100%;margin:4px 0 14px;font-size:13px}
th,td{padding:6px 10px;border-bottom:1px solid var(--line);text-align:right;
 font-variant-numeric:tabular-nums;white-space:nowrap}
th{font-size:11px;text-transform:uppercase;letter-spacing:.5px;color:var(--muted);font-weight:600;
 background:#f8fafc}
td.name,th.name{text-align:left;white-space:normal}
tr.best td{background:#ebfbee}
td .swatch{display:inline-block;width:10px;height:10px;border-radius:2px;margin-right:6px}
.up{color:#c92a2a}.down{color:#2b8a3e}.off{color:#c92a2a;font-weight:600}
.note{color:var(--muted);font-size:12px;margin:0 0 12px}
.why{margin:4px 0 14px;padding:0;list-style:none}
.why li{margin:3px 0}
footer{max-width:1180px;margin:0 auto;padding:0 28px 30px;color:var(--muted);font-size:12px}
)CSS";
}

const char* report_script() {
  return R"JS(
(function () {
  "use strict";
  function clock(t) {
    var s = Math.round(t), h = Math.floor(s / 3600), m = Math.floor(s / 60) % 60, r = s % 60;
    var mm = (h > 0 && m < 10 ? "0" : "") + m, ss = (r < 10 ? "0" : "") + r;
    return (h > 0 ? h + ":" : "") + mm + ":" + ss;
  }
  // Index of the last point at or before t (points are in time order).
  function at(times, t) {
    var lo = 0, hi = times.length - 1;
    if (hi < 0 || t < times[0]) return -1;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  var charts = document.querySelectorAll("svg.time-chart");
  Array.prototype.forEach.call(charts, function (svg) {
    var series = JSON.parse(svg.getAttribute("data-series"));
    var plot = svg.getAttribute("data-plot").split(",").map(Number);
    var tEnd = Number(svg.getAttribute("data-t-end"));
    var unit = svg.getAttribute("data-unit");
    var width = svg.viewBox.baseVal.width;
    var cursor = document.createElementNS(svg.namespaceURI, "line");
    cursor.setAttribute("class", "cursor");
    cursor.setAttribute("y1", plot[1]);
    cursor.setAttribute("y2", plot[1] + plot[3]);
    cursor.style.display = "none";
    svg.appendChild(cursor);
    var tip = document.createElement("div");
    tip.className = "tooltip";
    tip.style.display = "none";
    svg.parentNode.appendChild(tip);
    function hide() { cursor.style.display = "none"; tip.style.display = "none"; }
    svg.addEventListener("mouseleave", hide);
    svg.addEventListener("mousemove", function (ev) {
      var box = svg.getBoundingClientRect();
      var x = (ev.clientX - box.left) * width / box.width;
      if (x < plot[0] || x > plot[0] + plot[2]) { hide(); return; }
      var t = (x - plot[0]) / plot[2] * tEnd;
      cursor.setAttribute("x1", x);
      cursor.setAttribute("x2", x);
      cursor.style.display = "";
      tip.textContent = "";
      var head = document.createElement("div");
      head.textContent = "t = " + clock(t) + " (" + t.toFixed(1) + " s)";
      tip.appendChild(head);
      series.forEach(function (s) {
        if (s.faint) return;
        var i = at(s.t, t);
        var row = document.createElement("div");
        var sw = document.createElement("i");
        sw.style.background = s.color;
        row.appendChild(sw);
        var v = i < 0 ? 0 : s.v[i];
        row.appendChild(document.createTextNode(
            (series.length > 1 ? s.name + ": " : "") +
            (Number.isInteger(v) ? String(v) : v.toFixed(v < 100 ? 1 : 0)) + " " + unit));
        tip.appendChild(row);
      });
      var fig = svg.parentNode.getBoundingClientRect();
      var left = ev.clientX - fig.left + 14;
      if (left > fig.width - 220) left = ev.clientX - fig.left - 220;
      tip.style.left = left + "px";
      tip.style.top = (ev.clientY - fig.top + 10) + "px";
      tip.style.display = "";
    });
  });
  document.body.setAttribute("data-charts-ready", String(charts.length));
})();
)JS";
}

} // namespace ncjoule::report_detail
