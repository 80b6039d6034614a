#include "mpi/part_message.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace wideray {
namespace {

class ByteWriter {
public:
    template <class T>
    void put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::byte*>(&value);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }
    template <class T>
    void putArray(const std::vector<T>& values) {
        put(uint64_t(values.size()));
        const auto* p = reinterpret_cast<const std::byte*>(values.data());
        bytes.insert(bytes.end(), p, p + values.size() * sizeof(T));
    }
    void putString(const std::string& s) {
        put(uint64_t(s.size()));
        const auto* p = reinterpret_cast<const std::byte*>(s.data());
        bytes.insert(bytes.end(), p, p + s.size());
    }

    std::vector<std::byte> bytes;
};

class ByteReader {
public:
    explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

    template <class T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
    }
    template <class T>
    std::vector<T> getArray() {
        const uint64_t n = get<uint64_t>();
        if (n > (bytes_.size() - offset_) / sizeof(T)) throw std::runtime_error("truncated message");
        std::vector<T> values(n);
        if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
        return values;
    }
    std::string getString() {
        const std::vector<char> chars = getArray<char>();
        return {chars.begin(), chars.end()};
    }
    void expectEnd() const {
        if (offset_ != bytes_.size()) throw std::runtime_error("message longer than its content");
    }

private:
    const std::byte* take(size_t n) {
        if (n > bytes_.size() - offset_) throw std::runtime_error("truncated message");
        const std::byte* p = bytes_.data() + offset_;
        offset_ += n;
        return p;
    }
    std::span<const std::byte> bytes_;
    size_t offset_ = 0;
};

void putItem(ByteWriter& w, const WorkItem& item) {
    w.put(item.job);
    w.put(item.part);
    w.put(item.parts);
}

WorkItem getItem(ByteReader& r) {
    WorkItem item;
    item.job = r.get<uint32_t>();
    item.part = r.get<uint32_t>();
    item.parts = r.get<uint32_t>();
    return item;
}

} // namespace

std::vector<std::byte> encodeMessage(const RankMessage& message) {
    ByteWriter w;
    w.put(message.kind);
    if (message.kind == RankMessage::Kind::Failure) {
        putItem(w, message.item);
        w.putString(message.error);
    } else if (message.kind == RankMessage::Kind::Part) {
        const FramePart& p = message.part;
        putItem(w, p.item);
        w.put(p.width);
        w.put(p.height);
        w.put(p.tileSize);
        w.put(p.samplesPerPixel);
        w.put(p.aov);
        w.putArray(p.film.pixels);
        w.putArray(p.film.cost);
        w.put(p.film.primaryRays);
        w.put(p.film.secondaryRays);
        w.put(p.film.shadowRays);
        w.put(p.triangles);
        w.putString(p.accelName);
        w.putString(p.engine);
        w.put(p.buildSeconds);
    }
    return std::move(w.bytes);
}

RankMessage decodeMessage(std::span<const std::byte> bytes) {
    ByteReader r(bytes);
    RankMessage message;
    message.kind = r.get<RankMessage::Kind>();
    switch (message.kind) {
    case RankMessage::Kind::Ready: break;
    case RankMessage::Kind::Failure:
        message.item = getItem(r);
        message.error = r.getString();
        break;
    case RankMessage::Kind::Part: {
        FramePart& p = message.part;
        p.item = getItem(r);
        p.width = r.get<int>();
        p.height = r.get<int>();
        p.tileSize = r.get<int>();
        p.samplesPerPixel = r.get<int>();
        p.aov = r.get<Aov>();
        p.film.pixels = r.getArray<float>();
        p.film.cost = r.getArray<uint32_t>();
        p.film.primaryRays = r.get<uint64_t>();
        p.film.secondaryRays = r.get<uint64_t>();
        p.film.shadowRays = r.get<uint64_t>();
        p.triangles = r.get<uint64_t>();
        p.accelName = r.getString();
        p.engine = r.getString();
        p.buildSeconds = r.get<double>();
        break;
    }
    default: throw std::runtime_error("unknown message kind");
    }
    r.expectEnd();
    return message;
}

} // namespace wideray
