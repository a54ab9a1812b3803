#pragma once

namespace tntn {

void initialize_gdal_once();

} //namespace tntn
