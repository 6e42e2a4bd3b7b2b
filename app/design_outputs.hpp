// `design`'s files in an output folder: the journal (journal.csv, from which a stopped sweep
// resumes), designs.csv, pareto.csv and the figures, as runDesign hands them over.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/design.hpp"
#include "nocdyn/tables/design.hpp"

namespace nocdyn::app {

/// The files of a sweep in the folder `dir` (created, with its parents, when the journal opens).
class DesignFolder final : public DesignSink {
public:
    explicit DesignFolder(std::string dir) : dir_(std::move(dir)) {}
    std::vector<tables::DesignRecord> open(const std::string& signature, const std::vector<std::string>& columns,
                                           std::size_t parameters, std::size_t metrics) override;
    [[nodiscard]] std::string journal() const override;
    void append(const tables::DesignRecord& record) override;
    void designs(const std::string& name, const std::vector<std::string>& columns,
                 const std::vector<tables::DesignRecord>& records) override;
    void figure(const std::string& stem, const render::Figure& figure) override;

private:
    [[nodiscard]] std::string path(const std::string& name) const;
    std::string dir_;
    std::optional<tables::DesignJournal> journal_;
};

}  // namespace nocdyn::app
