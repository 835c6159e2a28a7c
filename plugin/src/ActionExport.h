#pragma once
/// "Export storeys…": asks for a folder and the formats, then writes the
/// selected Storey cloud (as it is in CloudCompare) one file per storey with
/// the core's writeStoreyFiles() (core/export/storey_files.h).
class ccHObject;
class ccMainAppInterface;

namespace storey::plugin {

void performExportStoreys(ccMainAppInterface* app, ccHObject* selected);

}  // namespace storey::plugin
