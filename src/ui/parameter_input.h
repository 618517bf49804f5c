#pragma once
// Number widgets for parameters (SetParameter ids): they edit a copy
// and commit through request_parameter, so a value out of range is refused
// with its valid range shown and the simulation keeps its last good value.
#include <string>

#include "ui/panel_context.h"
#include "ui/ui_requests.h"

namespace neurocloth {

// Widgets over request_parameter. Refusals go to ctx.messages.error; the field
// then shows the last accepted value again.
void parameter_field(PanelContext& ctx, const char* label, const ParameterId& id);
void parameter_slider(PanelContext& ctx, const char* label, const ParameterId& id);

}  // namespace neurocloth
