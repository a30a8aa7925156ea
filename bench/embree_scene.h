// The benchmarks' one way of handing a mesh to Embree 3, so that every comparison traces the same
// Embree scene: a new scene of `quality` on `device` holding the mesh's triangles (vertices as
// floats, as the ray sets' triangles are), ready for rtcCommitScene, which callers time.
#pragma once

#include <embree3/rtcore.h>

#include "io/obj_loader.h"

namespace glint {

inline RTCScene new_embree_scene(RTCDevice device, const ObjMesh& mesh, RTCBuildQuality quality) {
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        for (int a = 0; a < 3; ++a) v[3 * i + a] = float(mesh.vertices[i][a]);
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), mesh.triangles.size()));
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
        for (int a = 0; a < 3; ++a) index[3 * i + a] = mesh.triangles[i][a];
    rtcSetGeometryBuildQuality(g, quality);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    return scene;
}

}  // namespace glint
