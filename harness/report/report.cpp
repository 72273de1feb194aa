// Writing the gate's reports into a folder (report.h): every file or none.
#include "report.h"

#include "atomic_file.h"
#include "html_report.h"
#include "input_error.h"

#include <filesystem>
#include <system_error>
#include <utility>

namespace impulse::harness {

namespace {

std::string lower_first(std::string text) {
    if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z') {
        text[0] = static_cast<char>(text[0] - 'A' + 'a');
    }
    return text;
}

} // namespace

std::vector<std::string> report_fixed_files(const std::string& dir) {
    const std::filesystem::path base(dir);
    return {(base / "summary.md").string(), (base / "index.html").string()};
}

std::vector<std::pair<std::string, std::string>>
report_files(const std::string& dir, const std::vector<SceneCheck>& checks) {
    const std::filesystem::path base(dir);
    std::vector<std::pair<std::string, std::string>> files;
    files.emplace_back((base / "summary.md").string(), summary_markdown(checks));
    for (const auto& [name, content] : html_report_files(checks)) {
        files.emplace_back((base / name).string(), content);
    }
    return files;
}

void write_report(const std::string& dir,
                  const std::vector<std::pair<std::string, std::string>>& files) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(dir, error);
    if (error) {
        throw InputError(dir, "", "cannot be created (" + lower_first(error.message()) + ")");
    }
    if (!fs::is_directory(dir, error)) {
        throw InputError(dir, "", "cannot hold the report: it is not a directory");
    }
    // Written only when no path is refused (a link, a FIFO): never half new.
    for (const auto& [path, content] : files) {
        require_regular_or_missing(path);
    }
    for (const auto& [path, content] : files) {
        write_file_atomically(path, content);
    }
}

void write_report(const std::string& dir, const std::vector<SceneCheck>& checks) {
    write_report(dir, report_files(dir, checks));
}

} // namespace impulse::harness
