#pragma once
/// "Inspect SRPs" actions on the selected entity; the work itself is in
/// Inspect.h. Errors (nothing suitable selected, no SRPs) go to the console.
class ccHObject;
class ccMainAppInterface;

namespace storey::plugin {

/// "Inspect SRPs: colour by SRP": `selected` is a Storey cloud or an entity
/// of a run group (its map cloud is coloured).
void performColourBySrp(ccMainAppInterface* app, ccHObject* selected);

/// "Inspect SRPs: planes seen from a keyframe…": asks for the keyframe, shows
/// only the SRPs it observed and lists the observations in the console.
void performPlanesOfKeyframe(ccMainAppInterface* app, ccHObject* selected);

}  // namespace storey::plugin
