// SIGINT/SIGTERM handling: the handler only records the signal; the step
// loop stops at the next chance (between steps, or by failing the current
// Newton solve), keeps every finished step in curve.csv and says so in
// summary.json.
#pragma once

namespace pushout::interrupt
{
/// Installs the handlers for SIGINT and SIGTERM (after PetscInitialize,
/// whose handlers they replace), and the default action for SIGPIPE.
void install();

/// The signal received (0: none). Local to this process.
int received();
} // namespace pushout::interrupt
