// Two small scenes the render and --json tests build their runs from: a ball
// dropped onto a static floor (one collision), and the same at e = 0.5 left
// to bounce into a Zeno cascade (a run that stops early, partial).
#pragma once

#include <cmath>
#include <string>

namespace impulse::test {

inline constexpr double drop_g = 9.81;

// The ball's bottom starts 1 m above the floor, so it lands at
// t = sqrt(2 / g) = 0.4515 s, inside the 0.5 s run: one collision.
// expectations[0] holds (y at t = 0 is where the scene puts it),
// expectations[1] fails (x at t = 0 is 0, not 1).
inline std::string ball_scene(const std::string& name, double restitution = 0.5) {
    return R"({"schema":"impulse/scene@1","name":")" + name +
           R"(","dt":0.01,"duration":0.5,"restitution":)" + std::to_string(restitution) +
           R"(,"bodies":[{"name":"floor","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},)"
           R"({"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,1.5]}],)"
           R"("expectations":[{"kind":"state","body":"ball","t":0,"y":1.5,"atol":1e-12},)"
           R"({"kind":"state","body":"ball","t":0,"x":1,"atol":1e-12}]})";
}

// A disc dropped 4.5 m at e = 0.5 without "resting": the bounces end at
// t_inf = t1 (1 + 2e / (1 - e)) = 3 t1, t1 = sqrt(2 h / g), inside the 4 s
// run, where collisions alone cannot go on: the run stops just before.
inline std::string zeno_scene() {
    return R"({"schema":"impulse/scene@1","name":"zeno","dt":0.01,"duration":4,)"
           R"("restitution":0.5,"solver":{"integrator":"verlet"},)"
           R"("bodies":[{"name":"floor","static":true,"shape":{"box":[5,0.5]},"position":[0,-0.5]},)"
           R"({"name":"ball","shape":{"circle":0.5},"mass":1,"position":[0,5]}]})";
}
inline double zeno_end() {
    return 3.0 * std::sqrt(2.0 * 4.5 / drop_g);
}

} // namespace impulse::test
