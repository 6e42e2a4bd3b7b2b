// The analysis commands' figures, drawn from their results once the job has returned
// (app/outputs.hpp).
#include "app/envelope.hpp"
#include "app/loads.hpp"
#include "app/outputs.hpp"
#include "app/workspace.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

void writeEnvelopeFigure(const EnvelopeResult& result, const std::string& stem) {
    render::renderFigure(envelopeResultFigure(result), stem);
}

void writeLoadsFigure(const LoadsOptions& options, const LoadsResult& result, const std::string& stem) {
    render::renderFigure(loadsResultFigure(options, result), stem);
}

void writeWorkspaceFigure(const WorkspaceResult& result, const std::string& stem) {
    render::renderFigure(workspaceResultFigure(result), stem);
}

void writeFrequencyFigure(const WorkspaceResult& result, const std::string& stem) {
    render::renderFigure(frequencyResultFigure(result), stem);
}

}  // namespace nocdyn::app
