// The markup shared by the pictures (SVG), the HTML report and JUnit XML.
#pragma once

#include <string>

namespace impulse::harness {

// Text made safe for XML 1.0 (SVG, HTML, JUnit): & < > " ' escaped; control
// characters XML 1.0 forbids and invalid UTF-8 replaced by U+FFFD. In content
// tabs and line feeds stay; as an attribute value (attribute = true) they and
// carriage returns become character references, so parsers keep them.
std::string xml_escape(const std::string& text, bool attribute = false);

} // namespace impulse::harness
