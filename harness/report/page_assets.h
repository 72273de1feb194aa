// The report page's style sheet and script, compiled into the tool so the
// page is one self-contained file: no network, no server, any browser.
#pragma once

namespace impulse::harness {

// The CSS (page_style.cpp).
const char* page_style();
// Set before anything else runs: counts script errors into the <html>
// element's data-script-errors attribute, where a test (or a person in the
// inspector) can read them (page_script.cpp).
const char* page_error_hook();
// The replays, plots and keyboard (page_script.cpp). Plain JavaScript that
// reads each failed scene's JSON from <script type="application/json">.
const char* page_script();

} // namespace impulse::harness
