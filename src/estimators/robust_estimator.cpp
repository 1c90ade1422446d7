// The factory and name parser of the weight-function estimators (robust_estimator.h).
#include <pcl_ls3d/estimators/robust_estimator.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <utility>

namespace pcl_ls3d {

RobustEstimator::Ptr
makeRobustEstimator(RobustEstimatorType type, double constant)
{
  const bool given = std::isfinite(constant);
  switch (type) {
  case RobustEstimatorType::LEAST_SQUARES:
    return std::make_shared<LeastSquaresEstimator>();
  case RobustEstimatorType::ZUO:
    return std::make_shared<ZuoEstimator>(given ? constant : 6.0);
  case RobustEstimatorType::HUBER:
    return std::make_shared<HuberEstimator>(given ? constant : kHuber95);
  case RobustEstimatorType::TUKEY:
    return std::make_shared<TukeyEstimator>(given ? constant : kTukey95);
  case RobustEstimatorType::MD:
    return std::make_shared<MdEstimator>(given ? constant : kTukey95);
  }
  return nullptr;
}

RobustEstimator::Ptr
makeRobustEstimator(const RobustEstimatorChoice& choice)
{
  return makeRobustEstimator(choice.type, choice.constant);
}

namespace {

// Every spelling, the first of each type being the one toString() writes.
const std::pair<const char*, RobustEstimatorType> kNames[] = {
    {"ls", RobustEstimatorType::LEAST_SQUARES},
    {"least-squares", RobustEstimatorType::LEAST_SQUARES},
    {"zuo", RobustEstimatorType::ZUO},
    {"huber", RobustEstimatorType::HUBER},
    {"tukey", RobustEstimatorType::TUKEY},
    {"m", RobustEstimatorType::TUKEY},
    {"md", RobustEstimatorType::MD},
    {"m-d", RobustEstimatorType::MD},
    {"gm", RobustEstimatorType::MD}};

}  // namespace

bool
parseRobustEstimatorChoice(const std::string& text, RobustEstimatorChoice& choice, std::string* why)
{
  auto fail = [why](const std::string& reason) {
    if (why)
      *why = reason;
    return false;
  };
  std::string name = text.substr(0, text.find(':'));
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto* found = std::find_if(std::begin(kNames), std::end(kNames),
                                   [&](const auto& entry) { return name == entry.first; });
  if (found == std::end(kNames))
    return fail("unknown estimator '" + name + "' (ls, zuo, huber, tukey/m, md)");
  double constant = std::numeric_limits<double>::quiet_NaN();
  const std::size_t colon = text.find(':');
  if (colon != std::string::npos) {
    const std::string number = text.substr(colon + 1);
    char* end = nullptr;
    constant = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(constant) ||
        !(constant > 0.0))
      return fail("tuning constant of '" + name + "' must be a positive number, got '" + number + "'");
    if (found->second == RobustEstimatorType::LEAST_SQUARES)
      return fail("least squares has no tuning constant");
  }
  choice.type = found->second;
  choice.constant = constant;
  return true;
}

std::string
toString(const RobustEstimatorChoice& choice)
{
  const auto* found = std::find_if(std::begin(kNames), std::end(kNames),
                                   [&](const auto& entry) { return entry.second == choice.type; });
  std::string text = found == std::end(kNames) ? "?" : found->first;
  if (std::isfinite(choice.constant)) {
    char number[32];
    std::snprintf(number, sizeof number, ":%.17g", choice.constant);
    text += number;
  }
  return text;
}

RobustEstimator::Ptr
parseRobustEstimator(const std::string& text, std::string* why)
{
  RobustEstimatorChoice choice;
  return parseRobustEstimatorChoice(text, choice, why) ? makeRobustEstimator(choice) : nullptr;
}

}  // namespace pcl_ls3d
