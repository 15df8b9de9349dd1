// SPDX-License-Identifier: GPL-3.0-or-later
//
// pcl_cocone_reconstruction: see reconstruction_tool.cpp.
#include "reconstruction_tool.h"

int
main(int argc, char** argv)
{
  return pcl::cocone::tools::runReconstructionTool(argc, argv, nullptr);
}
