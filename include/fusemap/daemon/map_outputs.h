#ifndef FUSEMAP_DAEMON_MAP_OUTPUTS_H_
#define FUSEMAP_DAEMON_MAP_OUTPUTS_H_

// The run outputs moved to io/run_outputs.h, shared by fusemap_offline and fusemapd; this
// header stays for code that still includes it.
#include "fusemap/io/run_outputs.h"

#endif  // FUSEMAP_DAEMON_MAP_OUTPUTS_H_
