#include "island_lcp.h"

#include "lcp.h"

namespace impulse {

namespace {

// Temporary until islands.cpp lands: union-find over the dynamic ends of the
// links, islands numbered by their smallest body.
int root_of(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] >= 0) {
        const int up = parent[static_cast<std::size_t>(i)];
        if (parent[static_cast<std::size_t>(up)] >= 0) {
            parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(up)];
        }
        i = up;
    }
    return i;
}

} // namespace

void group_islands(const std::vector<Body>& bodies, const std::vector<IslandLink>& links,
                   Islands& out, IslandScratch& s) {
    const std::size_t n = bodies.size();
    s.parent.assign(n, -1);
    s.island_of.assign(n, -1);
    s.touched.assign(n, 0);
    for (const IslandLink& link : links) {
        s.touched[static_cast<std::size_t>(link.a)] = 1;
        if (bodies[static_cast<std::size_t>(link.b)].is_static()) {
            continue;
        }
        s.touched[static_cast<std::size_t>(link.b)] = 1;
        const int ra = root_of(s.parent, link.a);
        const int rb = root_of(s.parent, link.b);
        if (ra != rb) {
            s.parent[static_cast<std::size_t>(ra < rb ? rb : ra)] = ra < rb ? ra : rb;
        }
    }
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (s.touched[i] != 0) {
            const int r = root_of(s.parent, static_cast<int>(i));
            if (s.island_of[static_cast<std::size_t>(r)] < 0) {
                s.island_of[static_cast<std::size_t>(r)] = count++;
            }
            s.island_of[i] = s.island_of[static_cast<std::size_t>(r)];
        }
    }
    out.body_offsets.assign(static_cast<std::size_t>(count) + 1, 0);
    out.link_offsets.assign(static_cast<std::size_t>(count) + 1, 0);
    out.bodies.clear();
    out.links_of.clear();
    for (int isl = 0; isl < count; ++isl) {
        for (std::size_t i = 0; i < n; ++i) {
            if (s.touched[i] != 0 && s.island_of[i] == isl) {
                out.bodies.push_back(static_cast<int>(i));
            }
        }
        out.body_offsets[static_cast<std::size_t>(isl) + 1] = static_cast<int>(out.bodies.size());
        for (std::size_t l = 0; l < links.size(); ++l) {
            if (s.island_of[static_cast<std::size_t>(links[l].a)] == isl) {
                out.links_of.push_back(static_cast<int>(l));
            }
        }
        out.link_offsets[static_cast<std::size_t>(isl) + 1] = static_cast<int>(out.links_of.size());
    }
    if (count == 0) {
        out.body_offsets.clear();
        out.link_offsets.clear();
    }
}

IslandSolve solve_island(World& world, IslandProblem& problem, double /*tolerance*/) {
    const std::size_t n = problem.points.size();
    IslandSolve result;
    ++world.work.direct_solves;
    problem.A.resize(n * n);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i; j < n; ++j) {
            problem.A[i * n + j] = delassus(world, problem.points[i], problem.points[j]);
            problem.A[j * n + i] = problem.A[i * n + j];
        }
    }
    const LcpSolution solution = solve_lcp(problem.A, problem.q);
    result.solved = solution.solved;
    problem.lambda.assign(n, 0.0);
    if (solution.solved) {
        for (std::size_t i = 0; i < n; ++i) {
            problem.lambda[i] = solution.lambda[i];
        }
    }
    return result;
}

} // namespace impulse
