// Models: systems behind the integrators/system.hpp interface.
namespace nsb::models {}
