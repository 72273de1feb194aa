// The reference comparison over a list of scenes (comparison_run.h).
#include "comparison_run.h"

namespace impulse::harness {

ComparisonReport run_comparison(const std::vector<std::string>& paths,
                                const ComparisonRequest& request) {
    ComparisonReport report;
    report.references = request.references;
    report.skipped = request.skipped;
    report.notes = request.notes;
    report.engine = request.options.engine.name;
    report.engine_is_impulse = request.options.engine.kind == EngineSpec::Kind::impulse;
    report.scene_integrator = request.options.scene_integrator;
    CompareOptions options = request.options;
    options.references.clear();
    for (const ReferenceEngine& r : report.references) {
        options.references.push_back(r.spec);
        if (request.box2d_3_substeps && r.name == "box2d-3") {
            // Before the scene's path, which run_engine appends.
            options.references.back().command.insert(
                options.references.back().command.end(),
                {"--substeps", std::to_string(*request.box2d_3_substeps)});
        }
    }
    for (const std::string& path : paths) {
        if (request.on_start) {
            request.on_start(path);
        }
        report.scenes.push_back(compare_engines(path, options));
        if (request.on_done) {
            request.on_done();
        }
    }
    return report;
}

} // namespace impulse::harness
