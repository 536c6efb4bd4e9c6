#include "lcp/lcp.hpp"

namespace nsb::lcp {}
