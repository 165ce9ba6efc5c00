#include "core/mikktspace.h"

#include "core/mesh_tangents.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <unordered_map>

// Mikkelsen 2008, "Simulation of Wrinkled Surfaces Revisited" (master's thesis, University of
// Copenhagen), §3–4, and the structure of his reference mikktspace.c (2011), which is what the
// bakers run; the steps below follow it so that the same input gives the same frames:
//  1. weld corners whose position, normal and UV are all identical;
//  2. set aside degenerate triangles (two corners at one position), keeping the others' order;
//  3. per triangle, the UV derivatives dP/ds and dP/dt (thesis eq. 18, 19), normalised, with
//     the sign of the UV area ("orientation preserving") and their magnitudes; a triangle
//     without UV area or derivative length may join any group ("group with any");
//  4. group the triangles around each welded vertex that share an edge and an orientation;
//  5. per group, the tangent: each triangle's dP/ds projected into the plane of the vertex's
//     normal, weighted by the triangle's angle at the vertex, summed and normalised;
//  6. degenerate triangles' corners copy the frame of the first valid corner at their vertex.
// The arithmetic is done in float in the reference's order of operations.

namespace velvet {
namespace {

struct V3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;
};
V3 of(glm::vec3 v) {
    return {v.x, v.y, v.z};
}
V3 add(V3 a, V3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
V3 sub(V3 a, V3 b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V3 scale(float s, V3 v) {
    return {s * v.x, s * v.y, s * v.z};
}
float dot(V3 a, V3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
float length(V3 v) {
    return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}
/// The reference's zero test: anything above the smallest normal float counts.
bool notZero(float x) {
    return std::abs(x) > std::numeric_limits<float>::min();
}
bool notZero(V3 v) {
    return notZero(v.x) || notZero(v.y) || notZero(v.z);
}
V3 normalize(V3 v) {
    return scale(1.0f / length(v), v);
}
bool equal(V3 a, V3 b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}
/// @p v without its component along unit @p n, normalised unless nothing is left.
V3 projected(V3 v, V3 n) {
    const V3 r = sub(v, scale(dot(n, v), n));
    return notZero(r) ? normalize(r) : r;
}

constexpr unsigned kOrientPreserving = 1; ///< the triangle's UV area is positive
constexpr unsigned kGroupWithAny = 2;     ///< no UV derivatives: joins any neighbouring group

/// The reference splits a vertex's group where two triangles' projected derivatives are more
/// than an angular threshold apart; its default, 180 degrees, gives cos = -1 in float: only
/// exactly opposite derivatives split.
constexpr float kThresholdCos = -1.0f;

struct Triangle {
    std::array<int, 3> v{};         ///< welded vertex of each corner
    std::uint32_t original = 0;     ///< triangle number in mesh.indices
    std::array<int, 3> neighbour{}; ///< across edge i (corner i to corner i + 1), or -1
    std::array<int, 3> group{};     ///< the group of corner i, or -1
    V3 os;                          ///< normalised dP/ds, times -1 when not orientation-preserving
    V3 ot;                          ///< normalised dP/dt, likewise
    unsigned flags = kGroupWithAny; ///< assumed bad until its derivatives are found
    int corner(int vertex) const { return v[0] == vertex ? 0 : v[1] == vertex ? 1 : 2; }
    bool orientPreserving() const { return (flags & kOrientPreserving) != 0; }
};

/// The triangles around one welded vertex that share edges and an orientation. A group is
/// complete before the next starts, so all groups' faces lie in one array, each group a run.
struct Group {
    int vertex;
    bool orientPreserving;
    size_t first = 0, count = 0; ///< the group's run in Groups::faces
};
struct Groups {
    std::vector<Group> groups;
    std::vector<int> faces;
    std::span<const int> of(const Group& g) const { return {faces.data() + g.first, g.count}; }
};

/// A corner's frame: the reference's placeholder until a group defines it.
struct Space {
    V3 os{1.0f, 0.0f, 0.0f};
    bool orientPreserving = false;
    bool defined = false;
};

/// The first vertex with the same position, normal and UV as each vertex (exact float equality,
/// under which -0 equals +0; NaN equals nothing, so such a vertex stays its own).
std::vector<int> weld(const MeshData& mesh) {
    using Key = std::array<std::uint32_t, 8>;
    struct Hash {
        size_t operator()(const Key& k) const {
            size_t h = 1469598103934665603ull;
            for (std::uint32_t w : k)
                h = (h ^ w) * 1099511628211ull;
            return h;
        }
    };
    std::unordered_map<Key, int, Hash> first;
    first.reserve(mesh.vertices.size());
    std::vector<int> rep(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const Vertex& v = mesh.vertices[i];
        const float values[8] = {v.position.x, v.position.y, v.position.z, v.normal.x,
                                 v.normal.y,   v.normal.z,   v.uv.x,       v.uv.y};
        Key key;
        bool nan = false;
        for (int k = 0; k < 8; ++k) {
            nan |= std::isnan(values[k]);
            const float value = values[k] == 0.0f ? 0.0f : values[k];
            std::memcpy(&key[k], &value, 4);
        }
        rep[i] = nan ? int(i) : first.try_emplace(key, int(i)).first->second;
    }
    return rep;
}

/// Per-triangle derivatives (reference: InitTriInfo; thesis eq. 18, 19).
void initTriangle(Triangle& tri, const MeshData& mesh) {
    const Vertex& a = mesh.vertices[tri.v[0]];
    const Vertex& b = mesh.vertices[tri.v[1]];
    const Vertex& c = mesh.vertices[tri.v[2]];
    const float t21x = b.uv.x - a.uv.x, t21y = b.uv.y - a.uv.y;
    const float t31x = c.uv.x - a.uv.x, t31y = c.uv.y - a.uv.y;
    const V3 d1 = sub(of(b.position), of(a.position));
    const V3 d2 = sub(of(c.position), of(a.position));
    const float signedArea = t21x * t31y - t21y * t31x;
    const V3 os = sub(scale(t31y, d1), scale(t21y, d2));
    const V3 ot = add(scale(-t31x, d1), scale(t21x, d2));
    if (signedArea > 0.0f)
        tri.flags |= kOrientPreserving;
    if (!notZero(signedArea))
        return;
    const float absArea = std::abs(signedArea);
    const float lenOs = length(os), lenOt = length(ot);
    const float sign = tri.orientPreserving() ? 1.0f : -1.0f;
    if (notZero(lenOs))
        tri.os = scale(sign / lenOs, os);
    if (notZero(lenOt))
        tri.ot = scale(sign / lenOt, ot);
    // The magnitudes |dP/ds| and |dP/dt| (the reference keeps them for its full output); a
    // triangle is valid when both are non-zero.
    if (notZero(lenOs / absArea) && notZero(lenOt / absArea))
        tri.flags &= ~kGroupWithAny;
}

/// Pairs each edge with one running the other way (reference: BuildNeighborsFast). Edges sorted
/// by (lower vertex, higher vertex, triangle); each unpaired edge takes the first unpaired
/// opposite edge after it, which fixes the pairs where more than two triangles share an edge.
void findNeighbours(std::vector<Triangle>& tris, int valid) {
    struct Edge {
        int i0, i1, f, e;
    };
    std::vector<Edge> edges;
    edges.reserve(tris.size() * 3);
    for (int f = 0; f < valid; ++f)
        for (int e = 0; e < 3; ++e) {
            const int a = tris[f].v[e], b = tris[f].v[(e + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), f, e});
        }
    std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
        return x.i0 != y.i0 ? x.i0 < y.i0 : x.i1 != y.i1 ? x.i1 < y.i1 : x.f < y.f;
    });
    for (size_t i = 0; i < edges.size(); ++i) {
        const Edge& ea = edges[i];
        Triangle& ta = tris[ea.f];
        if (ta.neighbour[ea.e] != -1)
            continue;
        const int a0 = ta.v[ea.e], a1 = ta.v[(ea.e + 1) % 3];
        for (size_t j = i + 1; j < edges.size() && edges[j].i0 == ea.i0 && edges[j].i1 == ea.i1;
             ++j) {
            const Edge& eb = edges[j];
            Triangle& tb = tris[eb.f];
            if (tb.v[eb.e] == a1 && tb.v[(eb.e + 1) % 3] == a0 && tb.neighbour[eb.e] == -1) {
                ta.neighbour[ea.e] = eb.f;
                tb.neighbour[eb.e] = ea.f;
                break;
            }
        }
    }
}

/// Grows group @p g from the triangles on @p stack through edges at the group's vertex, in the
/// reference's depth-first order (AssignRecur: the neighbour across edge i, then across edge
/// i - 1): the first group a "group with any" triangle joins sets its orientation, the only
/// order dependence of the algorithm.
void growGroup(std::vector<Triangle>& tris, Groups& groups, int g, std::vector<int>& stack) {
    while (!stack.empty()) {
        Triangle& tri = tris[stack.back()];
        const int t = stack.back();
        stack.pop_back();
        Group& group = groups.groups[size_t(g)];
        const int i = tri.corner(group.vertex);
        if (tri.group[i] != -1)
            continue;
        if ((tri.flags & kGroupWithAny) && tri.group[0] == -1 && tri.group[1] == -1 &&
            tri.group[2] == -1)
            tri.flags = (tri.flags & ~kOrientPreserving) |
                        (group.orientPreserving ? kOrientPreserving : 0u);
        if (tri.orientPreserving() != group.orientPreserving)
            continue;
        groups.faces.push_back(t);
        ++group.count;
        tri.group[i] = g;
        if (const int right = tri.neighbour[i > 0 ? i - 1 : 2]; right >= 0)
            stack.push_back(right);
        if (const int left = tri.neighbour[i]; left >= 0)
            stack.push_back(left);
    }
}

/// One group per corner of a valid triangle not yet grouped (reference: Build4RuleGroups).
Groups buildGroups(std::vector<Triangle>& tris, int valid) {
    Groups groups;
    groups.faces.reserve(tris.size() * 3);
    std::vector<int> stack;
    for (int f = 0; f < valid; ++f)
        for (int i = 0; i < 3; ++i) {
            Triangle& tri = tris[f];
            if ((tri.flags & kGroupWithAny) || tri.group[i] != -1)
                continue;
            const int g = int(groups.groups.size());
            groups.groups.push_back({tri.v[i], tri.orientPreserving(), groups.faces.size(), 1});
            groups.faces.push_back(f);
            tri.group[i] = g;
            stack.clear();
            if (const int right = tri.neighbour[i > 0 ? i - 1 : 2]; right >= 0)
                stack.push_back(right);
            if (const int left = tri.neighbour[i]; left >= 0)
                stack.push_back(left);
            growGroup(tris, groups, g, stack);
        }
    return groups;
}

/// The tangent of a set of triangles around @p vertex (reference: EvalTspace): each valid
/// triangle's dP/ds in the normal's plane, weighted by its angle at the vertex.
V3 groupTangent(std::span<const int> faces, const std::vector<Triangle>& tris, const MeshData& mesh,
                int vertex) {
    V3 sum;
    const V3 n = of(mesh.vertices[vertex].normal);
    for (const int f : faces) {
        const Triangle& tri = tris[f];
        if (tri.flags & kGroupWithAny)
            continue;
        const int i = tri.corner(vertex);
        const V3 os = projected(tri.os, n);
        const V3 p0 = of(mesh.vertices[tri.v[i > 0 ? i - 1 : 2]].position);
        const V3 p1 = of(mesh.vertices[tri.v[i]].position);
        const V3 p2 = of(mesh.vertices[tri.v[i < 2 ? i + 1 : 0]].position);
        const V3 e1 = projected(sub(p0, p1), n), e2 = projected(sub(p2, p1), n);
        const float cosine = std::clamp(dot(e1, e2), -1.0f, 1.0f);
        const float angle = float(std::acos(double(cosine)));
        sum = add(sum, scale(angle, os));
    }
    return notZero(sum) ? normalize(sum) : sum;
}

/// Buffers groupSpaces() reuses from one group to the next.
struct Scratch {
    std::vector<V3> os, ot;
    std::vector<int> members, subgroupMembers;
    std::vector<size_t> subgroupStart; ///< each subgroup's run in subgroupMembers, and the end
    std::vector<V3> subgroupTangents;
};

/// The frames of one group's corners (reference: GenerateTSpaces). Each triangle's corner takes
/// the frame of the triangles of the group whose projected derivatives agree with its own
/// within the threshold; equal member sets share one evaluation.
void groupSpaces(std::span<const int> faces, const Group& group, int g,
                 const std::vector<Triangle>& tris, const MeshData& mesh,
                 std::vector<Space>& spaces, Scratch& s) {
    const V3 n = of(mesh.vertices[group.vertex].normal);
    // Each face's derivatives projected into the normal's plane once (the reference projects
    // them again for every pair; the same floats either way).
    s.os.resize(faces.size());
    s.ot.resize(faces.size());
    for (size_t k = 0; k < faces.size(); ++k) {
        s.os[k] = projected(tris[faces[k]].os, n);
        s.ot[k] = projected(tris[faces[k]].ot, n);
    }
    s.subgroupMembers.clear();
    s.subgroupStart.assign(1, 0);
    s.subgroupTangents.clear();
    for (size_t k = 0; k < faces.size(); ++k) {
        const int f = faces[k];
        const Triangle& tf = tris[f];
        const int index = tf.group[0] == g ? 0 : tf.group[1] == g ? 1 : 2;
        std::vector<int>& members = s.members;
        members.clear();
        for (size_t j = 0; j < faces.size(); ++j) {
            const int t = faces[j];
            const bool any = ((tf.flags | tris[t].flags) & kGroupWithAny) != 0;
            if (any || f == t ||
                (dot(s.os[k], s.os[j]) > kThresholdCos && dot(s.ot[k], s.ot[j]) > kThresholdCos))
                members.push_back(t);
        }
        std::sort(members.begin(), members.end());
        size_t l = 0;
        const size_t subgroups = s.subgroupTangents.size();
        while (l < subgroups &&
               !std::equal(members.begin(), members.end(),
                           s.subgroupMembers.begin() + std::ptrdiff_t(s.subgroupStart[l]),
                           s.subgroupMembers.begin() + std::ptrdiff_t(s.subgroupStart[l + 1])))
            ++l;
        if (l == subgroups) {
            s.subgroupMembers.insert(s.subgroupMembers.end(), members.begin(), members.end());
            s.subgroupStart.push_back(s.subgroupMembers.size());
            s.subgroupTangents.push_back(groupTangent(members, tris, mesh, group.vertex));
        }
        spaces[size_t(f) * 3 + size_t(index)] = {s.subgroupTangents[l], group.orientPreserving,
                                                 true};
    }
}

} // namespace

CornerTangents mikkTSpaceCornerTangents(const MeshData& mesh) {
    const size_t triangleCount = mesh.indices.size() / 3;
    const std::vector<int> rep = weld(mesh);

    // Valid triangles first, in their order; degenerate ones after (reference: DegenPrologue).
    std::vector<Triangle> tris, degenerate;
    tris.reserve(triangleCount);
    for (size_t t = 0; t < triangleCount; ++t) {
        Triangle tri;
        for (int i = 0; i < 3; ++i)
            tri.v[size_t(i)] = rep[mesh.indices[t * 3 + size_t(i)]];
        tri.original = std::uint32_t(t);
        tri.neighbour = {-1, -1, -1};
        tri.group = {-1, -1, -1};
        const V3 p0 = of(mesh.vertices[tri.v[0]].position);
        const V3 p1 = of(mesh.vertices[tri.v[1]].position);
        const V3 p2 = of(mesh.vertices[tri.v[2]].position);
        (equal(p0, p1) || equal(p0, p2) || equal(p1, p2) ? degenerate : tris).push_back(tri);
    }
    const int valid = int(tris.size());
    tris.insert(tris.end(), degenerate.begin(), degenerate.end());

    for (int f = 0; f < valid; ++f)
        initTriangle(tris[size_t(f)], mesh);
    findNeighbours(tris, valid);
    const Groups groups = buildGroups(tris, valid);
    Scratch scratch;
    std::vector<Space> spaces(tris.size() * 3);
    for (size_t g = 0; g < groups.groups.size(); ++g)
        groupSpaces(groups.of(groups.groups[g]), groups.groups[g], int(g), tris, mesh, spaces,
                    scratch);

    // Degenerate triangles' corners (reference: DegenEpilogue).
    std::unordered_map<int, size_t> firstCorner;
    for (size_t c = 0; c < size_t(valid) * 3; ++c)
        firstCorner.try_emplace(tris[c / 3].v[c % 3], c);
    for (size_t c = size_t(valid) * 3; c < tris.size() * 3; ++c)
        if (const auto it = firstCorner.find(tris[c / 3].v[c % 3]); it != firstCorner.end())
            spaces[c] = spaces[it->second];

    CornerTangents out;
    out.tangents.resize(triangleCount * 3);
    out.defined.assign(triangleCount * 3, 0);
    for (size_t c = 0; c < tris.size() * 3; ++c) {
        const size_t corner = size_t(tris[c / 3].original) * 3 + c % 3;
        const Space& s = spaces[c];
        const float len = length(s.os);
        if (s.defined && std::abs(len - 1.0f) < 1e-3f) {
            out.tangents[corner] =
                glm::vec4(s.os.x, s.os.y, s.os.z, s.orientPreserving ? -1.0f : 1.0f);
            out.defined[corner] = 1;
        } else {
            const glm::vec3 n = mesh.vertices[mesh.indices[corner]].normal;
            out.tangents[corner] = glm::vec4(anyOrthogonal(n), 1.0f);
        }
    }
    return out;
}

void generateMikkTSpaceTangents(MeshData& mesh) {
    const CornerTangents corners = mikkTSpaceCornerTangents(mesh);
    const size_t originalCount = mesh.vertices.size();
    std::vector<std::uint8_t> assigned(originalCount, 0);
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> copies;
    const auto same = [](const glm::vec4& a, const glm::vec4& b) {
        return std::memcmp(&a, &b, sizeof a) == 0;
    };
    for (size_t c = 0; c < corners.tangents.size(); ++c) {
        const std::uint32_t v = mesh.indices[c];
        const glm::vec4& t = corners.tangents[c];
        if (!assigned[v]) {
            mesh.vertices[v].tangent = t;
            assigned[v] = 1;
            continue;
        }
        if (same(mesh.vertices[v].tangent, t))
            continue;
        std::vector<std::uint32_t>& list = copies[v];
        const auto found = std::find_if(list.begin(), list.end(), [&](std::uint32_t u) {
            return same(mesh.vertices[u].tangent, t);
        });
        if (found != list.end()) {
            mesh.indices[c] = *found;
            continue;
        }
        Vertex copy = mesh.vertices[v];
        copy.tangent = t;
        mesh.indices[c] = std::uint32_t(mesh.vertices.size());
        list.push_back(mesh.indices[c]);
        mesh.vertices.push_back(copy);
    }
    for (size_t v = 0; v < originalCount; ++v)
        if (!assigned[v])
            mesh.vertices[v].tangent = glm::vec4(anyOrthogonal(mesh.vertices[v].normal), 1.0f);
}

void generateMikkTSpaceTangents(MeshData& mesh, size_t firstVertex, size_t vertexCount,
                                size_t firstIndex, size_t indexCount) {
    if (firstVertex == 0 && vertexCount == mesh.vertices.size() && firstIndex == 0 &&
        indexCount == mesh.indices.size()) {
        generateMikkTSpaceTangents(mesh);
        return;
    }
    MeshData part;
    part.vertices.assign(mesh.vertices.begin() + std::ptrdiff_t(firstVertex),
                         mesh.vertices.begin() + std::ptrdiff_t(firstVertex + vertexCount));
    part.indices.reserve(indexCount);
    for (size_t i = firstIndex; i < firstIndex + indexCount; ++i)
        part.indices.push_back(mesh.indices[i] - std::uint32_t(firstVertex));
    generateMikkTSpaceTangents(part);
    std::copy_n(part.vertices.begin(), vertexCount,
                mesh.vertices.begin() + std::ptrdiff_t(firstVertex));
    const auto extra = std::uint32_t(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), part.vertices.begin() + std::ptrdiff_t(vertexCount),
                         part.vertices.end());
    for (size_t i = 0; i < part.indices.size(); ++i) {
        const std::uint32_t v = part.indices[i];
        mesh.indices[firstIndex + i] = v < vertexCount ? std::uint32_t(firstVertex + v)
                                                       : extra + std::uint32_t(v - vertexCount);
    }
}

} // namespace velvet
