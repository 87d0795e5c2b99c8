// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file psOpenVDBTestGrids.h
 * @brief Point data grids written with OpenVDB for the reader's tests: random
 * points with int, half-float, double, vec3 and string attributes and a group.
 */
#ifndef psOpenVDBTestGrids_h
#define psOpenVDBTestGrids_h

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>
#include <openvdb/points/PointGroup.h>

#include <random>
#include <string>
#include <vector>

namespace pointsurfaces_test
{
namespace ovp = openvdb::points;

struct Source
{
  std::vector<openvdb::Vec3d> P;
  std::vector<int> Id;
  std::vector<float> Scale;
  std::vector<double> Density;
  std::vector<openvdb::Vec3f> Velocity;
  std::vector<std::string> Name;
  std::vector<short> Odd;
};

// A point data grid of `s`, positions through the codec `Codec`.
template<typename Codec>
inline ovp::PointDataGrid::Ptr MakeGrid(const Source& s, double voxel, const std::string& name)
{
  ovp::PointAttributeVector<openvdb::Vec3d> positions(s.P);
  auto xform = openvdb::math::Transform::createLinearTransform(voxel);
  auto index =
    openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(positions, *xform);
  auto grid = ovp::createPointDataGrid<Codec, ovp::PointDataGrid>(*index, positions, *xform);
  auto& tree = grid->tree();
  using IndexTree = openvdb::tools::PointIndexTree;
  ovp::appendAttribute<int>(tree, "id");
  ovp::populateAttribute<ovp::PointDataTree, IndexTree, ovp::PointAttributeVector<int>>(
    tree, index->tree(), "id", ovp::PointAttributeVector<int>(s.Id));
  ovp::appendAttribute(
    tree, "pscale", ovp::TypedAttributeArray<float, ovp::TruncateCodec>::attributeType());
  ovp::populateAttribute<ovp::PointDataTree, IndexTree, ovp::PointAttributeVector<float>>(
    tree, index->tree(), "pscale", ovp::PointAttributeVector<float>(s.Scale));
  ovp::appendAttribute<double>(tree, "density");
  ovp::populateAttribute<ovp::PointDataTree, IndexTree, ovp::PointAttributeVector<double>>(
    tree, index->tree(), "density", ovp::PointAttributeVector<double>(s.Density));
  ovp::appendAttribute<openvdb::Vec3f>(tree, "v");
  ovp::populateAttribute<ovp::PointDataTree, IndexTree, ovp::PointAttributeVector<openvdb::Vec3f>>(
    tree, index->tree(), "v", ovp::PointAttributeVector<openvdb::Vec3f>(s.Velocity));
  ovp::appendAttribute<std::string>(tree, "name");
  ovp::populateAttribute<ovp::PointDataTree, IndexTree, ovp::PointAttributeVector<std::string>>(
    tree, index->tree(), "name", ovp::PointAttributeVector<std::string>(s.Name));
  ovp::appendGroup(tree, "odd");
  ovp::setGroup(tree, index->tree(), s.Odd, "odd");
  grid->setName(name);
  return grid;
}

inline Source MakeSource(int n, double offset, int firstId, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Source s;
  const char* names[] = { "H", "C", "N", "O" };
  for (int i = 0; i < n; ++i)
  {
    s.P.emplace_back(offset + u(rng), u(rng), u(rng));
    s.Id.push_back(firstId + i);
    s.Scale.push_back(static_cast<float>(0.01 + 0.05 * (1.0 + u(rng))));
    s.Density.push_back(1e-300 * (i + 1));
    s.Velocity.emplace_back(
      static_cast<float>(u(rng)), static_cast<float>(u(rng)), static_cast<float>(1e6 * u(rng)));
    s.Name.emplace_back(names[i % 4]);
    s.Odd.push_back(static_cast<short>((firstId + i) % 2));
  }
  return s;
}
} // namespace pointsurfaces_test

#endif
