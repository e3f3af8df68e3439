#pragma once
// A request to stop a run early, from SIGINT or SIGTERM. The signal handler only records the
// signal (all it may safely do); the run loop reads the record at the start of each step and
// ends the run there, so that the results written are those of a whole step.
namespace vdec {

// Installs the handlers for SIGINT and SIGTERM, unless the signal is ignored (as the parent left
// it). Each handler is reset to the default action as it runs (SA_RESETHAND): a second signal of
// the same kind ends the process at once.
void installInterruptHandlers();

// The signal that asked the run to stop (SIGINT or SIGTERM), 0 when none has.
int interruptSignal();

// "SIGINT", "SIGTERM", or "" for 0.
const char* signalName(int signal);

// Records a request as the handler does (for tests), or with 0 withdraws it.
void setInterruptSignal(int signal);

}  // namespace vdec
