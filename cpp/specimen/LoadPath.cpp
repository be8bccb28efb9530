#include "LoadPath.h"
#include "../scene/KeyDef.h"
#include "../scene/SceneError.h"
#include <sstream>

namespace pushout::specimen
{
void check_load_path(const std::string& key, const std::vector<double>& path,
                     std::int64_t per_segment)
{
  if (path.size() < 2)
    throw SceneError("'" + key +
                     "' has no segment: it needs 0 and at least one more "
                     "displacement [mm] (e.g. [0.0, 0.02, 0.0, 0.1])");
  if (path[0] != 0.0)
    throw SceneError("'" + key + "' must start at 0: the path starts from the state after step 0 " +
                     "(a push-out's thermal step and corrosion stage, a joint's normal preload), " +
                     "where nothing is displaced yet");
  const KeyDef* per_segment_key = find_key("loading.steps_per_segment");
  const double steps = double(path.size() - 1) * double(per_segment);
  if (steps > per_segment_key->max)
  {
    std::ostringstream s;
    s << "'loading.steps_per_segment' times the " << path.size() - 1 << " segments of '" << key
      << "' is " << std::int64_t(steps) << " steps, more than "
      << std::int64_t(per_segment_key->max)
      << " (a step takes milliseconds to seconds: more would run for days)";
    throw SceneError(s.str());
  }
}
} // namespace pushout::specimen
