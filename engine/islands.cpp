#include "islands.h"

#include "index.h"

#include <algorithm>
#include <cstddef>

namespace impulse {

namespace {

// Path halving: every other node on the way up points to its grandparent, so
// later finds are short without a second pass or recursion.
int root_of(std::vector<int>& parent, int i) {
    while (parent[at(i)] != i) {
        parent[at(i)] = parent[at(parent[at(i)])];
        i = parent[at(i)];
    }
    return i;
}

// Enters a dynamic body into the union-find the first time a link names it;
// a static body never joins (the floor under two piles keeps them apart).
void enter(const std::vector<Body>& bodies, int i, IslandScratch& s) {
    if (bodies[at(i)].is_static() || s.parent[at(i)] >= 0) {
        return;
    }
    s.parent[at(i)] = i;
    s.touched.push_back(i);
}

// The smaller index becomes the root: the root of an island is then its
// smallest body whatever the order of the links, which orders the islands.
void unite(std::vector<int>& parent, int a, int b) {
    const int ra = root_of(parent, a);
    const int rb = root_of(parent, b);
    if (ra < rb) {
        parent[at(rb)] = ra;
    } else if (rb < ra) {
        parent[at(ra)] = rb;
    }
}

// The dynamic body of a link (-1 when both are static: such a link is in no island).
int dynamic_end(const std::vector<Body>& bodies, const IslandLink& link) {
    if (!bodies[at(link.a)].is_static()) {
        return link.a;
    }
    return bodies[at(link.b)].is_static() ? -1 : link.b;
}

// offsets[k + 1] holds island k's count on entry, its end on return.
void prefix_sums(std::vector<int>& offsets) {
    for (std::size_t i = 1; i < offsets.size(); ++i) {
        offsets[i] += offsets[i - 1];
    }
}

// Numbers the islands by their smallest body and places each island's bodies,
// ascending. touched must be sorted: a root is the smallest body of its
// island, so it comes before every other body of it.
void place_bodies(Islands& out, IslandScratch& s) {
    out.body_offsets.assign(1, 0);
    for (const int i : s.touched) {
        const int root = root_of(s.parent, i);
        if (root == i) {
            s.island_of[at(i)] = static_cast<int>(out.body_offsets.size()) - 1;
            out.body_offsets.push_back(0);
        }
        s.island_of[at(i)] = s.island_of[at(root)];
        ++out.body_offsets[at(s.island_of[at(i)]) + 1];
    }
    prefix_sums(out.body_offsets);
    out.bodies.resize(s.touched.size());
    s.cursor.assign(out.body_offsets.begin(), out.body_offsets.end() - 1);
    for (const int i : s.touched) {
        out.bodies[at(s.cursor[at(s.island_of[at(i)])]++)] = i;
    }
}

// Places each link in its dynamic body's island, keeping the order given.
void place_links(const std::vector<Body>& bodies, const std::vector<IslandLink>& links,
                 Islands& out, IslandScratch& s) {
    out.link_offsets.assign(out.body_offsets.size(), 0);
    for (const IslandLink& link : links) {
        const int d = dynamic_end(bodies, link);
        if (d >= 0) {
            ++out.link_offsets[at(s.island_of[at(d)]) + 1];
        }
    }
    prefix_sums(out.link_offsets);
    out.links_of.resize(at(out.link_offsets.back()));
    s.cursor.assign(out.link_offsets.begin(), out.link_offsets.end() - 1);
    for (std::size_t l = 0; l < links.size(); ++l) {
        const int d = dynamic_end(bodies, links[l]);
        if (d >= 0) {
            out.links_of[at(s.cursor[at(s.island_of[at(d)])]++)] = static_cast<int>(l);
        }
    }
}

} // namespace

void find_islands(const std::vector<Body>& bodies, const std::vector<IslandLink>& links,
                  Islands& out, IslandScratch& scratch) {
    if (scratch.parent.size() < bodies.size()) {
        scratch.parent.resize(bodies.size(), -1);
        scratch.island_of.resize(bodies.size(), -1);
    }
    scratch.touched.clear();
    for (const IslandLink& link : links) {
        enter(bodies, link.a, scratch);
        enter(bodies, link.b, scratch);
        if (!bodies[at(link.a)].is_static() && !bodies[at(link.b)].is_static()) {
            unite(scratch.parent, link.a, link.b);
        }
    }
    // The only super-linear term: O(T log T) for the T bodies touched. It gives
    // the islands their order and each island's bodies theirs.
    std::sort(scratch.touched.begin(), scratch.touched.end());
    place_bodies(out, scratch);
    place_links(bodies, links, out, scratch);
    // Reset only what this call touched, so the next costs O(its links) too.
    for (const int i : scratch.touched) {
        scratch.parent[at(i)] = -1;
        scratch.island_of[at(i)] = -1;
    }
    scratch.touched.clear();
}

} // namespace impulse
