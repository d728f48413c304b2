// Linked with every object of bounce_runtime and nothing else of the core
// (tests/install/CMakeLists.txt): the build fails when a file of the runtime
// calls into the rest of the core, and unit.Runtime.LinksAlone reads which
// shared libraries the runtime brings with it.
int main() { return 0; }
