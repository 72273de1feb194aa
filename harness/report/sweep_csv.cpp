#include "sweep_csv.h"

#include "number_format.h"

#include <cmath>
#include <sstream>

namespace impulse::harness {

namespace {

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) {
        return text;
    }
    std::string quoted = "\"";
    for (const char c : text) {
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    return quoted + "\"";
}

std::string csv_number(double value) {
    return std::isfinite(value) ? format_double(value) : "";
}

} // namespace

// For an engine other than impulse one more column, cost_source (engine,
// process or in-process), and its toi and ccd columns empty (the scene's own).
std::string sweep_csv(const SweepResult& r) {
    std::ostringstream out;
    const bool other_engine = !r.cost_source.empty();
    out << "engine,family,dt,integrator,toi,toi_tolerance,ccd,substeps,velocity_iterations,"
           "position_iterations,ok,error,cost_median,cost_spread,steps,narrow_phase_queries,"
           "toi_iterations,collisions,on_front,failure"
        << (other_engine ? ",cost_source" : "") << (r.pile ? ",energy_error" : "") << "\n";
    for (const SweepPoint& p : r.points) {
        out << (p.box2d ? std::string("box2d") : csv_field(p.engine)) << "," << csv_field(p.family)
            << "," << format_double(p.dt) << ",";
        if (p.box2d) {
            out << ",,,," << p.substeps << "," << p.velocity_iterations << ","
                << p.position_iterations << ",";
        } else if (!p.reference.empty()) {
            out << ",,,," << (p.substeps > 0 ? std::to_string(p.substeps) : "") << ",,,";
        } else if (p.kind != EngineSpec::Kind::impulse) {
            out << integrator_name(p.integrator) << ",," << format_double(p.toi_tolerance)
                << ",,,,,";
        } else {
            out << integrator_name(p.integrator) << "," << toi_method_name(p.toi) << ","
                << format_double(p.toi_tolerance) << "," << (p.ccd ? "true" : "false") << ",,,,";
        }
        out << (p.ok ? "true" : "false") << "," << (p.ok ? csv_number(p.error) : "") << ","
            << (p.ok ? csv_number(p.cost_median) : "") << ","
            << (p.ok ? csv_number(p.cost_spread) : "") << ","
            << (p.work_counted ? std::to_string(p.work.steps) : "") << ","
            << p.work.narrow_phase_queries << "," << p.work.toi_iterations << ","
            << p.work.collisions << "," << (p.on_front ? "true" : "false") << ","
            << csv_field(p.failure)
            << (other_engine ? std::string(",") + (p.ok ? sweep_cost_name(p.cost_source) : "") : "")
            << (r.pile ? "," + (p.ok ? csv_number(p.energy_error) : std::string()) : "") << "\n";
    }
    return out.str();
}

} // namespace impulse::harness
