// The report page's style sheet (page_assets.h).
#include "page_assets.h"

namespace impulse::harness {

// A constant, not a function body: the text is long, the function is one line.
constexpr const char* page_style_text = R"CSS(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; color: #222; margin: 2em auto;
       max-width: 1000px; padding: 0 1em; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; margin: 0 0 0.4em 0; }
.verdict { font-size: 1.1em; font-weight: bold; padding: 0.5em 0.8em; border-radius: 6px; }
.verdict.passed { background: #e8f5e9; color: #1b5e20; }
.verdict.failed { background: #fdecea; color: #8e1b10; }
table { border-collapse: collapse; width: 100%; margin: 1em 0 2em 0; font-size: 0.92em; }
th, td { text-align: left; padding: 0.35em 0.6em; border-bottom: 1px solid #e3e3e3;
         vertical-align: top; }
th { background: #f5f5f5; }
td.time { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
td.detail { word-break: break-word; }
.badge { display: inline-block; font-size: 0.8em; padding: 0.1em 0.6em; border-radius: 1em;
         font-weight: bold; vertical-align: middle; }
.badge.passed { background: #e8f5e9; color: #1b5e20; }
.badge.failed { background: #fdecea; color: #b71c1c; }
.badge.error { background: #fff3e0; color: #e65100; }
section { border: 1px solid #e3e3e3; border-left-width: 6px; border-radius: 6px; padding: 1em 1.2em;
          margin: 1.2em 0; }
section.passed { border-left-color: #43a047; }
section.failed { border-left-color: #e53935; }
section.error { border-left-color: #fb8c00; }
.files { color: #666; font-size: 0.88em; margin: 0.2em 0 0.6em 0; }
.files code { color: #333; }
.message { font-weight: bold; }
pre { background: #f7f7f7; border: 1px solid #e6e6e6; border-radius: 4px; padding: 0.8em;
      overflow-x: auto; font-size: 0.85em; line-height: 1.35; }
ul.expectations { padding-left: 1.2em; font-size: 0.92em; }
li.fail { color: #b71c1c; }
figure { margin: 1em 0 0 0; overflow-x: auto; }
figure svg { max-width: 100%; height: auto; }
figcaption { color: #666; font-size: 0.85em; }
a { color: #1565c0; }
details.scene { border: 1px solid #e3e3e3; border-left: 6px solid #43a047; border-radius: 6px;
                 padding: 0.4em 1.2em; margin: 0.6em 0; }
details.scene > summary { cursor: pointer; }
details.scene > summary h2 { display: inline; font-size: 1.05em; }
details.scene section { border: none; padding: 0; margin: 0.4em 0; }
.cause { font-size: 1.05em; background: #fff8e1; border-left: 4px solid #ffb300; padding: 0.5em 0.8em; }
.replay { margin: 1em 0; }
.controls { display: flex; flex-wrap: wrap; align-items: center; gap: 0.4em; margin-bottom: 0.3em; }
.controls button { font-size: 0.95em; padding: 0.25em 0.7em; border: 1px solid #999; border-radius: 4px;
                   background: #fafafa; cursor: pointer; }
.controls .clock { margin-left: 0.6em; font-variant-numeric: tabular-nums; }
.scrub { position: relative; height: 1.8em; }
.scrub input { width: 100%; margin: 0.3em 0 0 0; }
.divergence-marker { position: absolute; top: 0; width: 3px; height: 1.8em; margin-left: -1px;
                     background: #d32f2f; pointer-events: none; }
canvas.world { border: 1px solid #ddd; display: block; max-width: 100%; }
.legend, .sampling, .more { color: #555; font-size: 0.85em; margin: 0.3em 0; }
.key.gold { color: #c77c00; font-weight: bold; }
.key.new { color: #1565c0; font-weight: bold; }
.key.diverge { color: #d32f2f; font-weight: bold; }
.plots { display: flex; flex-wrap: wrap; gap: 0.6em 1em; }
.plot-title { font-size: 0.8em; color: #333; }
.plot canvas { border: 1px solid #eee; }
.keys { color: #666; font-size: 0.85em; }
)CSS";

const char* page_style() {
    return page_style_text;
}

} // namespace impulse::harness
