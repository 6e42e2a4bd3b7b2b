// nocdyn: kinematics and dynamics of any planar parallel robot by the natural orthogonal
// complement. The commands are in the nocdyn_commands library (app.cpp and cmd_*.cpp).
#include "app.hpp"

int main(int argc, char** argv) { return nocdyn::cli::runCommandLine(argc, argv); }
