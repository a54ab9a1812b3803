#pragma once

namespace tntn {

enum class MeshMode
{
    none,
    decomposed,
    triangles
};

} //namespace tntn
