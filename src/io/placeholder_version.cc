namespace fusemap {
namespace io {
// Version string written into outputs and checkpoints.
const char* FusemapVersion() { return "0.1.0"; }
}  // namespace io
}  // namespace fusemap
