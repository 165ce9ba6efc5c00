// The per-vertex visibility bake (render/mesh_visibility.h) against known answers: a convex
// mesh hides nothing from itself (share 1, bent normal the normal); a point on a floor under a
// coaxial ceiling disc whose rim is theta0 from the vertical sees the hemisphere but the cap
// theta < theta0, an open share of cos theta0 of its solid angle, with its bent normal straight
// up by symmetry; a point inside a closed box sees nothing (share 0, bent normal the normal);
// the same mesh gives the same values on every run.
#include "core/mesh.h"
#include "render/mesh_visibility.h"

#include <QTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

using namespace velvet;

namespace {

void addVertex(MeshData& m, glm::vec3 p, glm::vec3 n) {
    m.vertices.push_back(Vertex{p, n, glm::vec4(1, 0, 0, 1), glm::vec2(0)});
}

/// A floor (a square of half-side 4 at y = 0, facing up, its centre vertex 0) under a disc of
/// radius @p radius at height @p height facing down (a fan of @p sides triangles).
MeshData floorUnderDisc(float radius, float height, int sides) {
    MeshData m;
    addVertex(m, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const float h = 4.0f;
    for (glm::vec2 c : {glm::vec2(-h, -h), glm::vec2(h, -h), glm::vec2(h, h), glm::vec2(-h, h)})
        addVertex(m, glm::vec3(c.x, 0.0f, c.y), glm::vec3(0, 1, 0));
    for (std::uint32_t i = 0; i < 4; ++i) // counter-clockwise seen from above
        m.indices.insert(m.indices.end(), {0u, 1u + (i + 1) % 4, 1u + i});
    const std::uint32_t centre = std::uint32_t(m.vertices.size());
    addVertex(m, glm::vec3(0.0f, height, 0.0f), glm::vec3(0, -1, 0));
    for (int i = 0; i < sides; ++i) {
        const float a = 2.0f * std::numbers::pi_v<float> * float(i) / float(sides);
        addVertex(m, glm::vec3(radius * std::cos(a), height, radius * std::sin(a)),
                  glm::vec3(0, -1, 0));
    }
    for (int i = 0; i < sides; ++i)
        m.indices.insert(m.indices.end(), {centre, centre + 1 + std::uint32_t(i),
                                           centre + 1 + std::uint32_t((i + 1) % sides)});
    return m;
}

} // namespace

class TestRenderMeshVisibility : public QObject {
    Q_OBJECT
private slots:
    void convexMeshHidesNothing() {
        const MeshData sphere = makeSphere(1.0f, 32, 16);
        const auto v = render::bakeMeshVisibility(sphere);
        QCOMPARE(v.size(), sphere.vertices.size());
        for (size_t i = 0; i < v.size(); ++i) {
            QCOMPARE(v[i].w, 1.0f);
            // Every ray is open: the bent normal is the normal itself, not the samples' mean.
            QVERIFY2(glm::dot(glm::vec3(v[i]), glm::normalize(sphere.vertices[i].normal)) >
                         0.99999f,
                     qPrintable(QString("vertex %1").arg(i)));
        }
    }

    void floorUnderADiscSeesTheRing_data() {
        QTest::addColumn<float>("radius");
        QTest::addColumn<float>("height");
        QTest::newRow("R = H") << 1.0f << 1.0f;
        QTest::newRow("low ceiling") << 2.0f << 1.0f;
        QTest::newRow("high ceiling") << 0.5f << 1.0f;
    }
    void floorUnderADiscSeesTheRing() {
        QFETCH(float, radius);
        QFETCH(float, height);
        const MeshData m = floorUnderDisc(radius, height, 256);
        render::VisibilityBakeOptions options;
        options.raysPerVertex = 4096;
        const auto v = render::bakeMeshVisibility(m, options);
        QCOMPARE(v.size(), m.vertices.size());
        const float expected = height / std::sqrt(radius * radius + height * height);
        QVERIFY2(std::abs(v[0].w - expected) < 0.01f,
                 qPrintable(QString("open share %1, expected %2").arg(v[0].w).arg(expected)));
        QVERIFY2(glm::dot(glm::vec3(v[0]), glm::vec3(0, 1, 0)) > 0.995f, "bent normal not up");
        // The floor's corners, far from the disc, see almost all of their sky.
        QVERIFY(v[1].w > 0.97f);
    }

    void insideAClosedBoxSeesNothing() {
        MeshData box = makeCube(1.0f);
        // One more vertex, at the centre, facing +X: no triangle uses it, every ray hits a wall.
        addVertex(box, glm::vec3(0.0f), glm::vec3(1, 0, 0));
        const auto v = render::bakeMeshVisibility(box);
        QCOMPARE(v.back().w, 0.0f);
        QVERIFY(glm::dot(glm::vec3(v.back()), glm::vec3(1, 0, 0)) > 0.999f); // the normal
    }

    void sameMeshSameValues() {
        const MeshData ball = makeShaderBall(32);
        const auto a = render::bakeMeshVisibility(ball);
        const auto b = render::bakeMeshVisibility(ball);
        QVERIFY(a == b);
        // The shader ball hides parts of itself (the ring over the pedestal): not all open.
        int hidden = 0;
        for (const glm::vec4& x : a)
            hidden += x.w < 0.95f;
        QVERIFY(hidden > int(a.size() / 20));
    }

    void rayBudgetBoundsTheWork() {
        // With a budget below 16 rays a vertex each vertex still casts 16: the open share is a
        // multiple of 1/16.
        const MeshData m = floorUnderDisc(1.0f, 1.0f, 64);
        render::VisibilityBakeOptions options;
        options.rayBudget = 1;
        const auto v = render::bakeMeshVisibility(m, options);
        QCOMPARE(v.size(), m.vertices.size());
        QCOMPARE(std::fmod(v[0].w * 16.0f, 1.0f), 0.0f);
    }

    void emptyMeshGivesNothing() { QVERIFY(render::bakeMeshVisibility(MeshData{}).empty()); }
};

QTEST_GUILESS_MAIN(TestRenderMeshVisibility)
#include "test_render_mesh_visibility.moc"
