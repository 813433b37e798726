// Writes the OpenVDB fixtures of scene/tests/vdb.rs with OpenVDB itself, and what OpenVDB
// reads back from each file: the index box of the nonzero voxels, the sum of their
// values, and the trilinear field (tools::BoxSampler) at points in and around the grid.
//
//   apt-get install libopenvdb-dev libboost-dev
//   g++ -std=c++17 -O1 make_vdb.cpp -o /tmp/make_vdb -lopenvdb -ltbb -lImath-3_1
//   cd scene/tests/data/vdb && /tmp/make_vdb
//
// OpenVDB 10.0.1 (Debian 12) made the committed files.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace openvdb;

// Three blobs of random density (across root nodes, at negative coordinates) and two
// constant boxes that pruning turns into tiles (8^3 in a lower node, 128^3 in an upper
// one).
template <typename GridT>
typename GridT::Ptr smoke(const std::string& name, unsigned seed, double scale) {
    auto grid = GridT::create(0.0);
    grid->setName(name);
    grid->setGridClass(GRID_FOG_VOLUME);
    auto acc = grid->getAccessor();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Coord centres[3] = {Coord(-10, 7, 3), Coord(20, -30, 40), Coord(60, 45, -12)};
    for (const Coord& c : centres) {
        for (int x = -6; x <= 6; ++x)
            for (int y = -5; y <= 5; ++y)
                for (int z = -7; z <= 7; ++z) {
                    double r2 = (x * x) / 36.0 + (y * y) / 25.0 + (z * z) / 49.0;
                    if (r2 <= 1.0) acc.setValue(c.offsetBy(x, y, z), scale * (0.2 + u(rng)));
                }
    }
    grid->tree().fill(CoordBBox(Coord(-16, 16, 0), Coord(-9, 23, 7)), scale * 0.75, true);
    grid->tree().fill(CoordBBox(Coord(0, 0, 0), Coord(127, 127, 127)), scale * 0.125, true);
    grid->tree().prune();
    return grid;
}

math::Transform::Ptr scale_translate() {
    auto t = math::Transform::createLinearTransform(0.02);
    t->postTranslate(Vec3d(0.1, -0.3, 0.5));
    return t;
}

void write(const std::string& file, const GridPtrVec& grids, uint32_t compression) {
    io::File f(file);
    f.setCompression(compression);
    f.write(grids);
    f.close();
}

// What OpenVDB reads from `file`'s grid `name`, as JSON.
template <typename GridT>
std::string expect(const std::string& file, const std::string& name, unsigned seed) {
    io::File f(file);
    f.open();
    auto grid = gridPtrCast<GridT>(f.readGrid(name));
    f.close();
    Coord lo(INT32_MAX), hi(INT32_MIN);
    double sum = 0.0;
    for (auto it = grid->cbeginValueAll(); it; ++it) {
        if (*it == 0.0) continue;
        CoordBBox b;
        it.getBoundingBox(b);
        lo.minComponent(b.min());
        hi.maxComponent(b.max());
        sum += double(*it) * double(b.volume());
    }
    const auto& t = grid->transform();
    Vec3d min = t.indexToWorld(Vec3d(lo.x() - 1.5, lo.y() - 1.5, lo.z() - 1.5));
    Vec3d max = t.indexToWorld(Vec3d(hi.x() + 1.5, hi.y() + 1.5, hi.z() + 1.5));
    char buf[512];
    std::string json = "{\"file\": \"" + file + "\", \"grid\": \"" + name + "\", ";
    snprintf(buf, sizeof buf,
             "\"lo\": [%d, %d, %d], \"hi\": [%d, %d, %d], \"sum\": %.17g, "
             "\"min\": [%.17g, %.17g, %.17g], \"max\": [%.17g, %.17g, %.17g], \"samples\": [",
             lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), sum, min.x(), min.y(), min.z(),
             max.x(), max.y(), max.z());
    json += buf;
    // Points near nonzero voxels (centres and between them) and anywhere in the box.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Coord> on;
    for (auto it = grid->cbeginValueOn(); it; ++it)
        if (it.isVoxelValue()) on.push_back(it.getCoord());
    typename GridT::ConstAccessor acc = grid->getConstAccessor();
    for (int s = 0; s < 400; ++s) {
        Vec3d ijk;
        if (s % 2 == 0 && !on.empty()) {
            Coord c = on[size_t(u(rng) * on.size()) % on.size()];
            ijk = Vec3d(c.x(), c.y(), c.z());
            if (s % 4 == 2) ijk += Vec3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        } else {
            for (int k = 0; k < 3; ++k) ijk[k] = lo[k] - 1.5 + u(rng) * (hi[k] - lo[k] + 3.0);
        }
        double v = tools::BoxSampler::sample(acc, ijk);
        Vec3d w = t.indexToWorld(ijk);
        snprintf(buf, sizeof buf, "%s[%.17g, %.17g, %.17g, %.17g]", s ? ", " : "", w.x(), w.y(),
                 w.z(), v);
        json += buf;
    }
    return json + "]}";
}

int main() {
    initialize();
    const uint32_t blosc = io::COMPRESS_BLOSC | io::COMPRESS_ACTIVE_MASK;
    const uint32_t zip = io::COMPRESS_ZIP | io::COMPRESS_ACTIVE_MASK;

    auto density = smoke<FloatGrid>("density", 1, 1.0);
    density->setTransform(scale_translate());
    auto temperature = smoke<FloatGrid>("temperature", 2, 1500.0);
    temperature->setTransform(scale_translate());
    auto vel = Vec3SGrid::create();
    vel->setName("vel");
    vel->tree().setValue(Coord(1, 2, 3), Vec3s(1, 0, 0));
    write("smoke.vdb", GridPtrVec{density, temperature, vel}, blosc);
    write("smoke-zip.vdb", GridPtrVec{density}, zip);
    write("smoke-raw.vdb", GridPtrVec{density}, io::COMPRESS_ACTIVE_MASK);
    auto halves = density->deepCopy();
    halves->setSaveFloatAsHalf(true);
    write("smoke-half.vdb", GridPtrVec{halves}, blosc);

    // A double grid under an affine map with unequal scales, and an instance of it.
    auto dense = smoke<DoubleGrid>("density", 3, 2.0);
    Mat4d m = Mat4d::identity();
    m.setToScale(Vec3d(0.01, 0.02, 0.03));
    m.setTranslation(Vec3d(-1.0, 0.5, 2.0));
    dense->setTransform(math::Transform::Ptr(new math::Transform(math::MapBase::Ptr(new math::AffineMap(m)))));
    auto copy = dense->copyGrid();
    copy->setName("copy");
    write("double.vdb", GridPtrVec{dense, copy}, zip);

    // Grids prism refuses: a level set, a nonzero background, a rotated transform, a NaN.
    write("levelset.vdb", GridPtrVec{tools::createLevelSetSphere<FloatGrid>(0.3f, Vec3f(0), 0.1f)}, blosc);
    auto fogged = FloatGrid::create(0.5f);
    fogged->setName("density");
    fogged->tree().setValue(Coord(0, 0, 0), 1.0f);
    write("background.vdb", GridPtrVec{fogged}, blosc);
    auto turned = FloatGrid::create(0.0f);
    turned->setName("density");
    turned->tree().setValue(Coord(0, 0, 0), 1.0f);
    auto r = math::Transform::createLinearTransform(0.02);
    r->postRotate(0.3, math::Y_AXIS);
    turned->setTransform(r);
    write("rotated.vdb", GridPtrVec{turned}, blosc);
    auto broken = FloatGrid::create(0.0f);
    broken->setName("density");
    broken->tree().setValue(Coord(3, 1, 2), 0.5f);
    broken->tree().setValue(Coord(4, 1, 2), std::numeric_limits<float>::quiet_NaN());
    write("nan.vdb", GridPtrVec{broken}, blosc);

    FILE* out = fopen("expected.json", "w");
    fprintf(out, "[\n%s,\n%s,\n%s,\n%s,\n%s,\n%s,\n%s\n]\n",
            expect<FloatGrid>("smoke.vdb", "density", 11).c_str(),
            expect<FloatGrid>("smoke.vdb", "temperature", 12).c_str(),
            expect<FloatGrid>("smoke-zip.vdb", "density", 13).c_str(),
            expect<FloatGrid>("smoke-raw.vdb", "density", 14).c_str(),
            expect<FloatGrid>("smoke-half.vdb", "density", 15).c_str(),
            expect<DoubleGrid>("double.vdb", "density", 16).c_str(),
            expect<DoubleGrid>("double.vdb", "copy", 17).c_str());
    fclose(out);
    return 0;
}
