#include "caustica/distributed/communicator.h"

namespace caustica {
namespace {

class SingleProcess final : public Communicator {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    void sum(std::span<double>) override {}
    void sum(std::span<float>) override {}
    void sum(std::span<uint64_t>) override {}
    double max(double value) override { return value; }
    std::vector<std::vector<uint8_t>> allGather(std::span<const uint8_t> bytes) override {
        return {std::vector<uint8_t>(bytes.begin(), bytes.end())};
    }
    void broadcast(std::vector<uint8_t>&, int) override {}
    void barrier() override {}
    uint64_t bytesSent() const override { return 0; }
    uint64_t collectives() const override { return 0; }
};

}  // namespace

std::string Communicator::firstError(const std::string& message) {
    const auto all = allGather(std::span(reinterpret_cast<const uint8_t*>(message.data()), message.size()));
    for (size_t r = 0; r < all.size(); ++r)
        if (!all[r].empty())
            return size() == 1 ? std::string(all[r].begin(), all[r].end())
                               : "rank " + std::to_string(r) + ": " + std::string(all[r].begin(), all[r].end());
    return "";
}

Communicator& singleProcess() {
    static SingleProcess instance;  // stateless: safe to share between renders and threads
    return instance;
}

}  // namespace caustica
