// The files of a sweep (see design_outputs.hpp).
#include "app/design_outputs.hpp"

#include <filesystem>
#include <utility>

#include "app/outputs.hpp"
#include "nocdyn/error.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

std::string DesignFolder::path(const std::string& name) const { return (std::filesystem::path(dir_) / name).string(); }

std::vector<tables::DesignRecord> DesignFolder::open(const std::string& signature,
                                                     const std::vector<std::string>& columns, std::size_t parameters,
                                                     std::size_t metrics) {
    createOutputFolder(dir_, "out_dir");
    journal_.emplace(journal(), signature, columns, parameters, metrics);
    return journal_->previous();
}

std::string DesignFolder::journal() const { return path("journal.csv"); }

void DesignFolder::append(const tables::DesignRecord& record) {
    if (!journal_) throw Error("design: a design recorded before the journal was opened");
    journal_->append(record);
}

void DesignFolder::designs(const std::string& name, const std::vector<std::string>& columns,
                           const std::vector<tables::DesignRecord>& records) {
    tables::writeDesignTable(path(name), columns, records);
}

void DesignFolder::figure(const std::string& stem, const render::Figure& figure) {
    render::renderFigure(figure, path(stem));
}

}  // namespace nocdyn::app
