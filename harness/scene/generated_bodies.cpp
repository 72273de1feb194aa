#include "generated_bodies.h"

#include "strict_json.h"

#include <algorithm>

namespace impulse::harness {

SceneBody static_wall(const std::string& name, Vec2 position, double hx, double hy) {
    SceneBody body;
    body.name = name;
    body.is_static = true;
    body.shape = make_box(hx, hy);
    body.position = position;
    return body;
}

bool is_generated_name(const std::string& name, std::initializer_list<const char*> walls,
                       const std::string& prefix, int count) {
    for (const char* wall : walls) {
        if (name == wall) {
            return true;
        }
    }
    // At most 6 digits: more would be a count no block allows, and stol
    // must never overflow.
    if (name.rfind(prefix, 0) != 0 || name.size() == prefix.size() ||
        name.size() > prefix.size() + 6) {
        return false;
    }
    const std::string digits = name.substr(prefix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
        (digits.size() > 1 && digits[0] == '0')) {
        return false;
    }
    return std::stol(digits) < count;
}

// A scene has at most one block (the loader refuses both), so the block is
// known from the scene alone.
std::string body_path(const Scene& scene, std::size_t index) {
    if (index < scene.listed_bodies) {
        return json_element_path("bodies", index);
    }
    return scene.pile ? "pile" : "gas";
}

std::string body_reference(const Scene& scene, std::size_t index) {
    const std::string name = "'" + scene.bodies[index].name + "'";
    if (index < scene.listed_bodies) {
        return "bodies[" + std::to_string(index) + "] " + name;
    }
    return name + (scene.pile ? " of the pile block" : " of the gas block");
}

} // namespace impulse::harness
