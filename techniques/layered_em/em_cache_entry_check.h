#pragma once
// Whether a layered EM read from the cache is what baking `system` of `scene` under `settings`
// would give (Hakura & Snyder 2001 §4's preprocess, §5 draws from it): the counts the renderer
// indexes by, the scene objects it names, the cube-map size the parameters ask for, and finite
// geometry. The cache key says which bake an entry claims to be; this says whether its contents
// could be that bake, so that a damaged or foreign file is never drawn or printed.
#include <optional>
#include <string>

#include "techniques/layered_em/em_bake.h"

namespace hybridlab {

// Why `em` cannot be that bake ("layer 2 names object 4294967280; the scene has 12"), or nullopt
// when it fits.
std::optional<std::string> layeredEmEntryMismatch(const LayeredEm& em, const Scene& scene, const LensSystemInfo& system,
                                                  const EmBakeSettings& settings);

}  // namespace hybridlab
