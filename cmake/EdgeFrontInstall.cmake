# Install rules and the CMake package config (filled in by the packaging work).
