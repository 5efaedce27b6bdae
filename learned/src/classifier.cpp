// BOX-DNN and BOX-LSTM networks, their training and their model files (see classifier.hpp). The
// only translation unit of antcd that includes libtorch's headers.
#include <antcd/file.hpp>
#include <antcd/rng.hpp>
#include <antcd_learned/classifier.hpp>

#include "model_archive.hpp"

#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace antcd::learned {
namespace {

/// Format 2 added the decision threshold (covered by the checksum); format 1 files load with 0.5.
constexpr const char* kFormat = "antcd-learned/2";
constexpr const char* kFormat1 = "antcd-learned/1";
constexpr double kDefaultThreshold = 0.5;
constexpr std::int64_t kF = static_cast<std::int64_t>(kFeatureCount);
constexpr std::size_t kLstmWindow = 8;

struct MlpImpl : torch::nn::Module {
  MlpImpl()
      : l1(register_module("l1", torch::nn::Linear(kF, 64))),
        l2(register_module("l2", torch::nn::Linear(64, 32))),
        l3(register_module("l3", torch::nn::Linear(32, 1))) {}
  /// x: [n, 1, F] → logits [n].
  torch::Tensor forward(const torch::Tensor& x) {
    torch::Tensor h = torch::relu(l1(x.reshape({x.size(0), kF})));
    h = torch::relu(l2(h));
    return l3(h).reshape({x.size(0)});
  }
  torch::nn::Linear l1, l2, l3;
};
TORCH_MODULE(Mlp);

struct LstmNetImpl : torch::nn::Module {
  LstmNetImpl()
      : lstm(register_module("lstm",
                             torch::nn::LSTM(torch::nn::LSTMOptions(kF, 32).batch_first(true)))),
        out(register_module("out", torch::nn::Linear(32, 1))) {}
  /// x: [n, window, F] → logits [n].
  torch::Tensor forward(const torch::Tensor& x) {
    const torch::Tensor seq = std::get<0>(lstm(x));
    return out(seq.select(1, seq.size(1) - 1)).reshape({x.size(0)});
  }
  torch::nn::LSTM lstm;
  torch::nn::Linear out;
};
TORCH_MODULE(LstmNet);

/// libtorch's messages span several lines (and may carry a backtrace): keep the first line.
std::string first_line(const char* text) {
  std::string s(text);
  const auto nl = s.find('\n');
  if (nl != std::string::npos) s.resize(nl);
  return s;
}

/// FNV-1a over the bytes of float tensors, in order: libtorch's archive reader does not check the
/// zip's CRCs, so a model file records this sum of its contents and load() compares it.
std::int64_t checksum(const std::vector<torch::Tensor>& tensors) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const torch::Tensor& t : tensors) {
    const torch::Tensor c = t.contiguous();
    const auto* bytes = static_cast<const unsigned char*>(c.data_ptr());
    const std::size_t n = static_cast<std::size_t>(c.numel()) * c.element_size();
    for (std::size_t i = 0; i < n; ++i) {
      h ^= bytes[i];
      h *= 0x100000001B3ULL;
    }
    h ^= static_cast<std::uint64_t>(c.numel());
    h *= 0x100000001B3ULL;
  }
  return static_cast<std::int64_t>(h);
}

/// One intra-op thread: deterministic reductions, and no thread pool fighting the caller's.
void single_thread() {
  if (at::get_num_threads() != 1) at::set_num_threads(1);
}

}  // namespace

struct Classifier::Impl {
  Kind kind = Kind::Dnn;
  std::size_t window = 1;
  Scalar delta = 0;
  int feature_version = kFeatureVersion;
  TrainingRecord record;
  double threshold = kDefaultThreshold;
  torch::Tensor mean;    ///< [F]
  torch::Tensor stddev;  ///< [F]
  Mlp mlp{nullptr};
  LstmNet lstm{nullptr};

  void make_net() {
    if (kind == Kind::Dnn) {
      mlp = Mlp();
    } else {
      lstm = LstmNet();
    }
  }
  /// The tensors the checksum covers: standardisation, the network's parameters, then (from
  /// format 2) the decision threshold.
  std::vector<torch::Tensor> contents(bool with_threshold) {
    std::vector<torch::Tensor> v = {mean, stddev};
    for (const torch::Tensor& p : net().parameters()) v.push_back(p.detach());
    if (with_threshold) v.push_back(torch::tensor({threshold}, torch::kFloat64));
    return v;
  }
  torch::nn::Module& net() {
    return kind == Kind::Dnn ? static_cast<torch::nn::Module&>(*mlp)
                             : static_cast<torch::nn::Module&>(*lstm);
  }
  torch::Tensor logits(const torch::Tensor& x) {
    return kind == Kind::Dnn ? mlp->forward(x) : lstm->forward(x);
  }
  /// Raw samples [n, window, F] → standardised.
  torch::Tensor input(std::span<const float> samples, std::size_t count) const {
    const auto n = static_cast<std::int64_t>(count);
    const auto w = static_cast<std::int64_t>(window);
    torch::Tensor x =
        torch::from_blob(const_cast<float*>(samples.data()), {n, w, kF}, torch::kFloat32);
    return (x - mean) / stddev;
  }
};

std::string_view kind_name(Kind kind) { return kind == Kind::Dnn ? "box-dnn" : "box-lstm"; }

Kind parse_kind(std::string_view name) {
  if (name == "box-dnn") return Kind::Dnn;
  if (name == "box-lstm") return Kind::Lstm;
  throw Error("unknown learned method '" + std::string(name) + "' (expected box-dnn or box-lstm)");
}

std::size_t default_window(Kind kind) { return kind == Kind::Dnn ? 1 : kLstmWindow; }

Classifier::Classifier(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Classifier::Classifier(Classifier&&) noexcept = default;
Classifier& Classifier::operator=(Classifier&&) noexcept = default;
Classifier::~Classifier() = default;

Kind Classifier::kind() const { return impl_->kind; }
std::size_t Classifier::window() const { return impl_->window; }
Scalar Classifier::delta() const { return impl_->delta; }
int Classifier::feature_version() const { return impl_->feature_version; }
const TrainingRecord& Classifier::record() const { return impl_->record; }
void Classifier::set_record(const TrainingRecord& record) { impl_->record = record; }
double Classifier::threshold() const { return impl_->threshold; }
void Classifier::set_threshold(double threshold) {
  if (!(threshold > 0 && threshold < 1)) {
    throw std::invalid_argument("decision threshold " + std::to_string(threshold) +
                                " outside (0, 1)");
  }
  impl_->threshold = threshold;
}

Classifier Classifier::train(const Dataset& data, const TrainOptions& options) {
  if (data.size() == 0) throw std::invalid_argument("no training samples");
  if (data.features.size() != data.size() * data.sample_floats()) {
    throw std::invalid_argument("training samples and labels do not match");
  }
  if (options.kind == Kind::Dnn && data.window != 1) {
    throw std::invalid_argument("box-dnn trains on single frames (window 1)");
  }
  if (options.epochs < 1 || options.batch < 1 || !(options.learning_rate > 0)) {
    throw std::invalid_argument("epochs, batch and learning rate must be positive");
  }
  single_thread();
  torch::manual_seed(options.seed);

  auto impl = std::make_unique<Impl>();
  impl->kind = options.kind;
  impl->window = data.window;
  impl->delta = data.delta;
  const auto n = static_cast<std::int64_t>(data.size());
  const auto w = static_cast<std::int64_t>(data.window);
  const torch::Tensor x_raw =
      torch::from_blob(const_cast<float*>(data.features.data()), {n, w, kF}, torch::kFloat32)
          .clone();
  std::vector<float> label_values(data.labels.begin(), data.labels.end());
  const torch::Tensor y = torch::from_blob(label_values.data(), {n}, torch::kFloat32).clone();
  {
    const torch::Tensor flat = x_raw.reshape({n * w, kF});
    impl->mean = flat.mean(0);
    impl->stddev = flat.std(0, /*unbiased=*/false).clamp_min(1e-6);
    // Constant features stay constant (0) instead of being blown up.
    impl->stddev = torch::where(impl->stddev < 1e-5, torch::ones_like(impl->stddev), impl->stddev);
  }
  const torch::Tensor x = (x_raw - impl->mean) / impl->stddev;
  impl->make_net();
  torch::nn::Module& net = impl->net();
  net.train();
  torch::optim::Adam optim(net.parameters(), torch::optim::AdamOptions(options.learning_rate));

  const auto start = std::chrono::steady_clock::now();
  std::vector<std::int64_t> order(static_cast<std::size_t>(n));
  for (std::int64_t i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  std::uint64_t state = mix_seed(options.seed ^ 0x5348554646ULL);
  double last_loss = 0;
  for (std::size_t epoch = 0; epoch < options.epochs; ++epoch) {
    for (std::size_t i = order.size(); i > 1; --i) {  // Fisher-Yates with our own generator
      state = mix_seed(state);
      std::swap(order[i - 1], order[state % i]);
    }
    const torch::Tensor perm = torch::from_blob(order.data(), {n}, torch::kInt64);
    double sum = 0;
    std::int64_t batches = 0;
    for (std::int64_t b = 0; b < n; b += static_cast<std::int64_t>(options.batch)) {
      const std::int64_t e =
          std::min<std::int64_t>(n, b + static_cast<std::int64_t>(options.batch));
      const torch::Tensor idx = perm.slice(0, b, e);
      const torch::Tensor xb = x.index_select(0, idx);
      const torch::Tensor yb = y.index_select(0, idx);
      optim.zero_grad();
      const torch::Tensor loss = torch::binary_cross_entropy_with_logits(impl->logits(xb), yb);
      loss.backward();
      optim.step();
      sum += loss.item<double>();
      ++batches;
    }
    last_loss = sum / static_cast<double>(std::max<std::int64_t>(1, batches));
    if (options.log && ((epoch + 1) % 10 == 0 || epoch + 1 == options.epochs)) {
      std::ostringstream s;
      s << "  epoch " << epoch + 1 << "/" << options.epochs << ": loss " << last_loss;
      options.log(s.str());
    }
  }
  net.eval();
  impl->record.seed = options.seed;
  impl->record.samples = static_cast<std::uint64_t>(n);
  impl->record.positives = data.positives();
  impl->record.epochs = options.epochs;
  impl->record.final_loss = last_loss;
  impl->record.train_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Classifier c(std::move(impl));
  const std::vector<std::uint8_t> p = c.predict(data.features, data.size());
  std::size_t right = 0;
  for (std::size_t i = 0; i < p.size(); ++i) right += p[i] == data.labels[i] ? 1 : 0;
  c.impl_->record.train_accuracy = static_cast<double>(right) / static_cast<double>(p.size());
  return c;
}

std::vector<float> Classifier::probabilities(std::span<const float> samples,
                                             std::size_t count) const {
  if (samples.size() != count * impl_->window * kFeatureCount) {
    throw std::invalid_argument("expected " + std::to_string(count) + " samples of " +
                                std::to_string(impl_->window) + " x " +
                                std::to_string(kFeatureCount) + " features");
  }
  std::vector<float> out(count);
  if (count == 0) return out;
  const torch::NoGradGuard no_grad;
  const torch::Tensor p = torch::sigmoid(impl_->logits(impl_->input(samples, count))).contiguous();
  std::copy_n(p.data_ptr<float>(), count, out.begin());
  return out;
}

std::vector<std::uint8_t> Classifier::predict(std::span<const float> samples,
                                              std::size_t count) const {
  const std::vector<float> p = probabilities(samples, count);
  std::vector<std::uint8_t> out(p.size());
  const double t = impl_->threshold;
  for (std::size_t i = 0; i < p.size(); ++i) out[i] = static_cast<double>(p[i]) >= t ? 1 : 0;
  return out;
}

void Classifier::save(const std::filesystem::path& path) const {
  std::ostringstream bytes;
  try {
    torch::serialize::OutputArchive a;
    a.write("format", c10::IValue(std::string(kFormat)));
    a.write("feature_version", c10::IValue(static_cast<std::int64_t>(impl_->feature_version)));
    a.write("feature_count", c10::IValue(static_cast<std::int64_t>(kFeatureCount)));
    a.write("kind", c10::IValue(std::string(kind_name(impl_->kind))));
    a.write("window", c10::IValue(static_cast<std::int64_t>(impl_->window)));
    a.write("delta", c10::IValue(static_cast<double>(impl_->delta)));
    a.write("mean", impl_->mean);
    a.write("stddev", impl_->stddev);
    const TrainingRecord& r = impl_->record;
    a.write("record_seed", c10::IValue(static_cast<std::int64_t>(r.seed)));
    a.write("record_scenes", c10::IValue(static_cast<std::int64_t>(r.scenes)));
    a.write("record_frames", c10::IValue(static_cast<std::int64_t>(r.frames)));
    a.write("record_samples", c10::IValue(static_cast<std::int64_t>(r.samples)));
    a.write("record_positives", c10::IValue(static_cast<std::int64_t>(r.positives)));
    a.write("record_epochs", c10::IValue(static_cast<std::int64_t>(r.epochs)));
    a.write("record_final_loss", c10::IValue(r.final_loss));
    a.write("record_train_accuracy", c10::IValue(r.train_accuracy));
    a.write("record_data_seconds", c10::IValue(r.data_seconds));
    a.write("record_train_seconds", c10::IValue(r.train_seconds));
    a.write("record_meshes", c10::IValue(r.meshes));
    a.write("record_held_out", c10::IValue(r.held_out));
    a.write("record_threshold_source", c10::IValue(r.threshold_source));
    a.write("threshold", c10::IValue(impl_->threshold));
    torch::serialize::OutputArchive net;
    impl_->net().save(net);
    a.write("net", net);
    a.write("checksum", c10::IValue(checksum(impl_->contents(true))));
    a.save_to(bytes);
  } catch (const c10::Error& e) {
    throw Error(path.string() +
                ": cannot serialise the model: " + first_line(e.what_without_backtrace()));
  }
  write_file_atomic(path, bytes.str());
}

Classifier Classifier::load(const std::filesystem::path& path) {
  const std::string name = path.string();
  const auto fail = [&](const std::string& problem) -> ModelError {
    return ModelError(name + ": " + problem);
  };
  std::string bytes;
  try {
    bytes = read_file(path);
  } catch (const Error& e) {
    throw ModelError(first_line(e.what()));
  }
  // The zip structure and every entry's CRC-32 are checked before libtorch parses anything
  // (model_archive.hpp): its parsers are not made for damaged input.
  if (const std::string problem = detail::model_archive_problem(bytes); !problem.empty()) {
    throw fail(problem);
  }
  single_thread();
  auto impl = std::make_unique<Impl>();
  try {
    torch::serialize::InputArchive a;
    try {
      a.load_from(bytes.data(), bytes.size());
    } catch (const c10::Error& e) {
      throw fail("not an antcd learned model (" + first_line(e.what_without_backtrace()) + ")");
    }
    c10::IValue v;
    const auto text = [&](const char* key) {
      if (!a.try_read(key, v) || !v.isString()) throw fail(std::string("no '") + key + "' entry");
      return v.toStringRef();
    };
    const auto integer = [&](const char* key) {
      if (!a.try_read(key, v) || !v.isInt()) throw fail(std::string("no '") + key + "' entry");
      return v.toInt();
    };
    const auto real = [&](const char* key) {
      if (!a.try_read(key, v) || !v.isDouble()) throw fail(std::string("no '") + key + "' entry");
      return v.toDouble();
    };
    if (!a.try_read("format", v) || !v.isString() ||
        v.toStringRef().rfind("antcd-learned/", 0) != 0) {
      throw fail(std::string("not an antcd learned model (no format tag ") + kFormat + ")");
    }
    const bool format1 = v.toStringRef() == kFormat1;
    if (!format1 && v.toStringRef() != kFormat) {
      throw fail("model file format '" + v.toStringRef() + "', this antcd reads " + kFormat +
                 " and " + kFormat1 + ": train a new one with antcd learn train");
    }
    const std::int64_t version = integer("feature_version");
    if (version != kFeatureVersion || integer("feature_count") != kF) {
      throw fail("model made for feature version " + std::to_string(version) +
                 ", this antcd computes version " + std::to_string(kFeatureVersion) +
                 ": train a new one with antcd learn train");
    }
    impl->feature_version = static_cast<int>(version);
    impl->kind = parse_kind(text("kind"));
    const std::int64_t window = integer("window");
    if (window < 1 || window > 1024 || (impl->kind == Kind::Dnn && window != 1)) {
      throw fail("invalid window " + std::to_string(window));
    }
    impl->window = static_cast<std::size_t>(window);
    impl->delta = real("delta");
    if (!(impl->delta >= 0) || !std::isfinite(impl->delta)) throw fail("invalid delta");
    const auto stats = [&](const char* key) {
      torch::Tensor t;
      if (!a.try_read(key, t) || t.scalar_type() != torch::kFloat32 || t.dim() != 1 ||
          t.size(0) != kF || !torch::isfinite(t).all().item<bool>()) {
        throw fail(std::string("missing or invalid '") + key + "' entry");
      }
      return t;
    };
    impl->mean = stats("mean");
    impl->stddev = stats("stddev");
    if (!(impl->stddev > 0).all().item<bool>()) throw fail("invalid 'stddev' entry");
    TrainingRecord& r = impl->record;
    r.seed = static_cast<std::uint64_t>(integer("record_seed"));
    r.scenes = static_cast<std::uint64_t>(integer("record_scenes"));
    r.frames = static_cast<std::uint64_t>(integer("record_frames"));
    r.samples = static_cast<std::uint64_t>(integer("record_samples"));
    r.positives = static_cast<std::uint64_t>(integer("record_positives"));
    r.epochs = static_cast<std::uint64_t>(integer("record_epochs"));
    r.final_loss = real("record_final_loss");
    r.train_accuracy = real("record_train_accuracy");
    r.data_seconds = real("record_data_seconds");
    r.train_seconds = real("record_train_seconds");
    r.meshes = text("record_meshes");
    r.held_out = text("record_held_out");
    if (!format1) {
      r.threshold_source = text("record_threshold_source");
      impl->threshold = real("threshold");
      if (!(impl->threshold > 0 && impl->threshold < 1)) {
        throw fail("invalid decision threshold " + std::to_string(impl->threshold) +
                   " (expected inside (0, 1))");
      }
    }

    impl->make_net();
    torch::nn::Module& net = impl->net();
    std::vector<std::vector<std::int64_t>> shapes;
    for (const torch::Tensor& p : net.parameters()) shapes.push_back(p.sizes().vec());
    torch::serialize::InputArchive weights;
    if (!a.try_read("net", weights)) throw fail("no network parameters");
    net.load(weights);
    const auto params = net.parameters();
    for (std::size_t k = 0; k < params.size(); ++k) {
      if (params[k].sizes().vec() != shapes[k] || params[k].scalar_type() != torch::kFloat32 ||
          !torch::isfinite(params[k]).all().item<bool>()) {
        throw fail("network parameters do not fit a " + std::string(kind_name(impl->kind)) +
                   " model");
      }
    }
    if (integer("checksum") != checksum(impl->contents(!format1))) {
      throw fail("corrupt model file (its checksum does not match its contents)");
    }
    net.eval();
  } catch (const c10::Error& e) {
    throw fail("invalid model file (" + first_line(e.what_without_backtrace()) + ")");
  } catch (const ModelError&) {
    throw;
  } catch (const Error& e) {
    throw fail(first_line(e.what()));
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // libtorch's unpickler and TorchScript importer throw std::runtime_error, std::out_of_range
    // and torch::jit::ErrorReport on a damaged archive that passed the CRC check (one written
    // damaged): each is a bad file, never a crash.
    throw fail("invalid model file (" + first_line(e.what()) + ")");
  }
  return Classifier(std::move(impl));
}

}  // namespace antcd::learned
